; expect: 2:21 expected slot name
(deftemplate t (slot))
(exit)
