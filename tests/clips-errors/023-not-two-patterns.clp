; expect: 2:25 expected ')'
(defrule r (a) (not (b) (c)) => )
(exit)
