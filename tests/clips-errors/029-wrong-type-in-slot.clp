; expect: 5:21 expected type
; keeps: f-1     (counter (n 1))
(deftemplate counter (slot n (type INTEGER)))
(assert (counter (n 1)))
(assert (counter (n abc)))
(facts)
(exit)
