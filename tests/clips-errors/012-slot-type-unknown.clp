; expect: 2:30 expected type
(deftemplate t (slot a (type INTEGR)))
(exit)
