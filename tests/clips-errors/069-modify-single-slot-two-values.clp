; expect: 4:58 expected one value
; lacks: bump
(deftemplate counter (slot n))
(defrule bump ?c <- (counter (n ?n)) => (modify ?c (n ?n 1)))
(list-defrules)
(exit)
