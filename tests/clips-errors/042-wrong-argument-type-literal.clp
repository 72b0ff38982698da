; expect: 2:39 expected type
(defrule r (a ?x) => (printout t (+ 1 abc) crlf))
(exit)
