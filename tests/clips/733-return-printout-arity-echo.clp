; `(return 1 2)` is CLIPS's "return function" syntax error (shown up to the second
; value), `(printout)` its [ARGACCES4], each with the construct shown
(deffunction h1 () (return 1 2))
(deffunction h2 () (printout))
(deffunction h3 (?x) (if ?x then (return ?x (+ 1 2))))
(defrule r3 => (return 1 2))
(defrule r4 => (printout))
(return 1 2)
(printout)
(deffunction ok (?x) (return (+ ?x 1)))
(ok 1)
(list-deffunctions)
(rules)
(exit)
