; expect: 3:17 expected slot
(deftemplate robot (slot name))
(assert (robot (color red)))
(exit)
