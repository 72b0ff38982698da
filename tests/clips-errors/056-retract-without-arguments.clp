; expect: 2:23 expected argument
(defrule r (a ?x) => (retract))
(exit)
