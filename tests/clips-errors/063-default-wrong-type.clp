; expect: 2:48 expected type
(deftemplate t (slot a (type INTEGER) (default 1.5)))
(exit)
