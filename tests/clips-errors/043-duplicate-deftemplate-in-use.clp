; expect: 7:14 expected deftemplate
; keeps: f-1     (job (id 7))
; keeps: job 7
; lacks: f-1     (job (id 7) (prio nil))
(deftemplate job (slot id))
(defrule uses-job (job (id ?i)) => (printout t "job " ?i crlf))
(deftemplate job (slot id) (slot prio))
(assert (job (id 7)))
(facts)
(run)
(exit)
