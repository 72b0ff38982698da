; expect: 3:57 expected type
; lacks: f-1     (t (a x))
(deftemplate t (slot a (type INTEGER) (allowed-values 1 x)))
(assert (t (a x)))
(facts)
(exit)
