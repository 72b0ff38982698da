; expect: 2:28 expected variable
(defrule r (a ?x) => (bind x 1))
(exit)
