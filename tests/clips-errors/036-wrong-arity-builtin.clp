; expect: 2:35 expected argument
(defrule r (a ?x) => (printout t (sqrt ?x 2) crlf))
(exit)
