; expect: 3:17 expected slot
(deftemplate t (slot a))
(assert (t (a 1 2)))
(exit)
