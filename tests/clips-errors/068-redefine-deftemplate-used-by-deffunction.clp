; expect: 6:14 expected in use
; keeps: f-1     (job (id 7))
; lacks: f-1     (job (id 7) (prio nil))
(deftemplate job (slot id))
(deffunction new-job (?i) (assert (job (id ?i))))
(deftemplate job (slot id) (slot prio))
(new-job 7)
(facts)
(exit)
