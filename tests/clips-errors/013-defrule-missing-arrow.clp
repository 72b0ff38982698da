; expect: 2:39 expected '=>'
(defrule r (a ?x) (printout t ?x crlf))
(exit)
