; check-syntax returns the warnings reading a construct printed as its second field
; (an integer literal beyond 64 bits: [SCANNER1]); a command's warnings are lost; a
; pattern's bad first field is its own syntax error.
(check-syntax "(defrule example =>)")
(check-syntax "(defrule foo (number 40000000000000000000) =>)")
(check-syntax "(defrule example (3) =>)")
(check-syntax "(+ 1 40000000000000000000)")
(check-syntax "(defrule e3 (a) => (printout t 40000000000000000000))")
(check-syntax "(deffunction f () (+ -90000000000000000000 1))")
(check-syntax "(deffacts d (a 90000000000000000000))")
(check-syntax "(defglobal ?*g* = 90000000000000000000)")
(check-syntax "(defrule e4 (a 90000000000000000000) => (+ a))")
(check-syntax "(defrule e5 ([x]) =>)")
(check-syntax "(assert ([x]))")
(list-defrules)
(exit)
