(watch facts)
(watch rules)
(watch activations)
(deftemplate acc (slot n) (multislot log))
(defrule grow
   ?a <- (acc (n ?n&:(< ?n 4)) (log $?l))
   =>
   (modify ?a (n (+ ?n 1)) (log $?l ?n)))
(defrule report (acc (n 4) (log $?l)) => (printout t "log " ?l crlf))
(reset)
(assert (acc (n 0)))
(run)
(exit)
