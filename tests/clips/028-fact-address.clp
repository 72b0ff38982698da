(watch facts)
(watch rules)
(watch activations)
(deftemplate counter (slot name) (slot value (default 0)))
(defrule bump
   ?c <- (counter (name ?n) (value ?v&:(< ?v 3)))
   =>
   (modify ?c (value (+ ?v 1))))
(defrule consume
   ?t <- (token ?x)
   ?c <- (counter (name ?x))
   =>
   (retract ?t)
   (printout t "consumed token for " ?x crlf))
(reset)
(assert (counter (name a)))
(assert (token a))
(run)
(facts)
(exit)
