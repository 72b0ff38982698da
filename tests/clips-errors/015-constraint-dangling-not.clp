; expect: 2:16 expected constraint
(defrule r (a ~) => )
(exit)
