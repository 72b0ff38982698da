; exxpectedacks: f-1     (job (id 7) (prio nil))
(deftemplate job )
(deftemplate job (slot id))
(deffunction níw-job (?i) (assert (job ((job (id 7) (prio nil))
(deftemp
(defcccc(eq ccccob (slot id) (slot prio))
(new-job 7)
(facts)
(exit)
