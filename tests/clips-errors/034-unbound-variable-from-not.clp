; expect: 2:40 expected bound
(defrule r (not (a ?x)) => (printout t ?x crlf))
(exit)
