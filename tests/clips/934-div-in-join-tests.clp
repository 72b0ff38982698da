; div in join tests (field predicates and test CEs), as cryptarithm programs write
; them: the quotient is truncated toward zero, folds more than two arguments left,
; truncates float arguments first and reports a zero divisor
(watch rules)
(deftemplate n (slot v))
(deffacts numbers (n (v -7)) (n (v -3)) (n (v 0)) (n (v 2)) (n (v 3)) (n (v 7)) (n (v 15)))
(defrule halves
  (n (v ?a))
  (n (v ?b&:(= (div ?a 2) ?b)))
  =>
  (printout t ?a " div 2 = " ?b crlf))
(defrule carry
  (n (v ?a&:(> ?a 0)))
  (n (v ?b&~?a&:(> ?b 0)))
  (n (v ?c&:(= (+ (mod (* 2 ?a) 10) (div (+ ?a ?b) 10)) ?c)))
  =>
  (printout t "carry " ?a " " ?b " -> " ?c crlf))
(defrule three-args
  (n (v ?a))
  (n (v ?b&:(> ?b 0)))
  (test (= (div ?a ?b 2) 1))
  =>
  (printout t ?a " div " ?b " div 2 = 1" crlf))
(reset)
(run)
(defrule float-operand
  (n (v ?a))
  (n (v ?b&:(= (div 7.9 ?a) ?b)))
  =>
  (printout t "7.9 div " ?a " = " ?b crlf))
(run)
(defrule by-zero
  (n (v ?a&:(< ?a 0)))
  (n (v ?b&:(= (div ?a ?b) -1)))
  =>
  (printout t ?a " div " ?b " = -1" crlf))
(run)
(exit)
