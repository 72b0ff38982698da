; A not/forall group over several CEs that reads no variable of the patterns before it:
; CLIPS's join from the right has no test and checks no descent, so any partial match of
; the subnetwork blocks every left partial match (the oldest found first); which one
; blocks decides the order of what the group unblocks, and when.
(deftemplate it (slot id) (slot v))
(deftemplate mk (slot id))
(defrule r3 (it (id ?i)) (not (and (it (id ?j) (v y)) (not (mk (id ?j))))) =>)
(defrule q (it (id ?i)) (it (id ?j) (v y)) =>)
(defrule f (it (id ?i) (v z)) (forall (it (id ?j) (v y)) (mk (id ?j))) => (printout t "f " ?i crlf))
(deffacts s (it (id 1) (v y)) (it (id 2) (v z)) (it (id 3) (v z)))
(watch activations)
(reset)
(assert (mk (id 1)))
(assert (it (id 4) (v y)))
(assert (mk (id 4)))
(assert (it (id 5) (v y)) (it (id 6) (v z)))
(retract 5)
(assert (mk (id 5)))
(agenda)
(retract 4)
(run)
(exit)
