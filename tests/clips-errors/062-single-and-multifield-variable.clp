; expect: 2:29 expected variable
(defrule r (a ?x) (b ?x) (a $?x) => )
(exit)
