; expect: 5:41 expected type
; keeps: ok
; lacks: spawn
(deftemplate robot (slot speed (type INTEGER)))
(defrule spawn => (assert (robot (speed fast))))
(defrule ok => )
(list-defrules)
(exit)
