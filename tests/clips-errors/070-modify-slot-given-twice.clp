; expect: 3:52 expected slot
(deftemplate counter (slot n) (slot m))
(defrule bump ?c <- (counter) => (modify ?c (n 1) (n 2)))
(exit)
