; A rule added while facts exist whose only pattern is the first pattern of an older
; rule: CLIPS builds the rule's last join anew and primes it from the memory of the
; older rule's join, bucket by bucket (its left hash on ?i), so oldest fact first here;
; we keep that order on the host (`rete::order`).
(deftemplate it (slot id))
(deftemplate mk (slot id))
(watch activations)
(defrule a (it (id ?i)) (mk (id ?i)) =>)
(assert (it (id 1)) (it (id 2)) (mk (id 1)) (mk (id 2)) (it (id 3)))
(defrule c (it (id ?i)) =>)
(defrule b (it (id ?i)) (mk (id ?i)) => (printout t x crlf))
(exit)
