; expect: 2:45 expected allowed-values
(deftemplate t (slot a (allowed-symbols x) (allowed-values y)))
(exit)
