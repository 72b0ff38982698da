; expect: 3:21 expected closing '"'
(deftemplate note (slot text))
(assert (note (text "never closed)))
(exit)
