; expect: 2:25 expected attribute
(deftemplate t (slot a (colour red)))
(exit)
