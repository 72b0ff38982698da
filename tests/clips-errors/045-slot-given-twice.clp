; expect: 3:19 expected slot
(deftemplate t (slot a))
(assert (t (a 1) (a 2)))
(exit)
