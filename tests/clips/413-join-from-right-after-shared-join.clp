; A join from the right (not/exists/forall over several CEs) comes second among its
; parent's successors, right after the newest: when its subnetwork's first join is shared
; with an older rule's join, CLIPS passes a new left partial match to the join from the
; right before the subnetwork, which shows as a transient activation.
(deftemplate mk (slot id) (slot v))
(deftemplate d (slot id))
(deftemplate ctx (slot s))
(defrule r1 (ctx (s s3)) (mk (v y)) =>)
(defrule r1b (ctx (s s3)) (d (id 1)) =>)
(defrule r1c (ctx (s s3)) (d (id 2)) =>)
(defrule r3 (ctx (s s3)) (not (and (mk (id ?q) (v y)) (not (d (id ?q))))) =>)
(defrule r4 (ctx (s s2)) (mk (v y)) =>)
(defrule r5 (ctx (s s2)) (forall (mk (id ?q) (v y)) (d (id ?q))) =>)
(defrule r6 (ctx (s s2)) (exists (d (id 1)) (mk (v y))) =>)
(watch activations)
(watch rules)
(assert (mk (id 4) (v y)) (d (id 1)) (d (id 2)))
(assert (ctx (s s3)))
(assert (ctx (s s2)))
(agenda)
(assert (d (id 4)))
(run)
(exit)
