; expect: 3:13 expected template
(deftemplate robot (slot name))
(defrule r (robt (name ?n)) => )
(exit)
