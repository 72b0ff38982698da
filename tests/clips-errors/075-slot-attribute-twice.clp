; expect: 2:37 expected once
(deftemplate t (slot a (default 1) (default 2)))
(exit)
