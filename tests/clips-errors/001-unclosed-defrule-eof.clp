; expect: 6:1 expected ')'
(defrule r
   (a ?x)
   =>
   (printout t ?x crlf)
