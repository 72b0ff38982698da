; expect: 3:10 expected slot
(deftemplate t (slot id (default ?NONE)) (slot v))
(assert (t (v 1)))
(exit)
