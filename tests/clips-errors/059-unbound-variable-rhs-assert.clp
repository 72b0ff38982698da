; expect: 2:33 expected bound
(defrule r (a ?x) => (assert (b ?z)))
(exit)
