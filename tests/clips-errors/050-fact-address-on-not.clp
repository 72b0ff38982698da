; expect: 2:18 expected pattern
(defrule r ?f <- (not (a)) => )
(exit)
