; expect: 3:41 expected slot
(deftemplate robot (slot name))
(defrule r ?f <- (robot) => (modify ?f (speed 3)))
(exit)
