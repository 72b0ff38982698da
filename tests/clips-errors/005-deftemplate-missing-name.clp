; expect: 2:14 expected name
(deftemplate (slot a))
(exit)
