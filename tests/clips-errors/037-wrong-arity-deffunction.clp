; expect: 4:35 expected argument
; keeps: 3
(deffunction add (?a ?b) (+ ?a ?b))
(defrule r (a ?x) => (printout t (add ?x) crlf))
(add 1 2)
(exit)
