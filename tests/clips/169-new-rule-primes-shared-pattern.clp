; A rule added while facts exist whose only pattern is the first pattern of an older
; rule: CLIPS activates it oldest fact first (it builds the rule's last join anew and
; primes it from the alpha memory); we share that join and prime the new rule from its
; memory, newest first.
(deftemplate it (slot id))
(deftemplate mk (slot id))
(watch activations)
(defrule a (it (id ?i)) (mk (id ?i)) =>)
(assert (it (id 1)) (it (id 2)) (mk (id 1)) (mk (id 2)) (it (id 3)))
(defrule c (it (id ?i)) =>)
(defrule b (it (id ?i)) (mk (id ?i)) => (printout t x crlf))
(exit)
