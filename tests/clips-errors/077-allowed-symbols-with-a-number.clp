; expect: 2:44 expected type
(deftemplate t (slot a (allowed-symbols on 1)))
(exit)
