; expect: 2:24 expected expression
(defrule r (a ?x) (test) => )
(exit)
