; expect: 2:10 expected name
(defrule (a ?x) => (printout t ?x crlf))
(exit)
