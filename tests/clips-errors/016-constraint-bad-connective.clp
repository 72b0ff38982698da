; expect: 2:18 expected constraint
(defrule r (a ?x|&y) => )
(exit)
