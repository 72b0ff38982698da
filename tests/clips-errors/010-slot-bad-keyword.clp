; expect: 4:17 expected slot
; keeps: f-1     (good (a 2))
(deftemplate good (slot a))
(deftemplate t (slt a))
(assert (good (a 2)))
(facts)
(exit)
