; expect: 2:28 expected bound
(defrule r (a ?x) (test (> ?y 1)) => )
(exit)
