; expect: 2:56 expected type
(deftemplate t (slot a (type INTEGER) (default-dynamic x)))
(exit)
