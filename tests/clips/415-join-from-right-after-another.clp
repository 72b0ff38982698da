; A not/exists group over several CEs that comes after another such group: CLIPS 6.30
; gives its join from the right no test even when its subnetwork reads the variables
; of the patterns before it, so any partial match of the subnetwork blocks every left
; partial match (r2: mk 2 blocks it 1 too, for good); when the earlier group takes the
; match's own left partial match away, the others come back, newest on the agenda (r1).
; A plain not after a group keeps its test (r3), and so does the first group (r4).
(deftemplate it (slot id))
(deftemplate mk (slot id))
(deftemplate d (slot id))
(deftemplate q (slot id))
(defrule r1 (it (id ?i)) (not (and (mk (id ?i)) (not (d (id ?i))))) (not (and (mk (id ?i)) (not (d (id ?i))))) =>)
(defrule r2 (it (id ?i)) (not (and (q (id ?i)) (d (id ?i)))) (not (and (mk (id ?i)) (not (d (id ?i))))) =>)
(defrule r3 (it (id ?i)) (not (and (q (id ?i)) (d (id ?i)))) (not (mk (id ?i))) =>)
(defrule r4 (it (id ?i)) (not (and (mk (id ?i)) (not (d (id ?i))))) => (printout t "r4 " ?i crlf))
(defrule r5 (it (id ?i)) (not (and (q (id ?i)) (d (id ?i)))) (q (id ?j)) (exists (mk (id ?i)) (not (d (id ?i)))) => (printout t "r5 " ?i " " ?j crlf))
(watch activations)
(watch facts)
(assert (q (id 7)))
(assert (it (id 1)))
(assert (it (id 2)))
(assert (it (id 3)))
(assert (mk (id 2)))
(agenda)
(assert (d (id 2)))
(agenda)
(assert (it (id 4)))
(assert (mk (id 5)))
(retract 6)
(assert (mk (id 1)))
(agenda)
(retract 8)
(agenda)
(run)
(exit)
