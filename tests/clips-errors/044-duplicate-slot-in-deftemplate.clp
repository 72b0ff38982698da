; expect: 2:31 expected slot
(deftemplate t (slot a) (slot a))
(exit)
