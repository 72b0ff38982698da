; expect: 2:35 expected single
(deftemplate t (slot s (default a b)))
(exit)
