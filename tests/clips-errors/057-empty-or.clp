; expect: 2:22 expected pattern
(defrule r (a ?x) (or) => )
(exit)
