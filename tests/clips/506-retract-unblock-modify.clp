; A modify whose retract unblocks a not: the old fact is not seen below the not, the
; new one arrives after.
(watch rules)
(watch activations)
(deftemplate s (slot id) (slot st))
(deffunction show (?a ?b) (printout t "join " ?a " " ?b crlf) TRUE)
(deffacts start (s (id 1) (st busy)) (s (id 2) (st idle)) (s (id 3) (st idle)))
(defrule r1 (s (id ?i) (st idle)) (not (s (st busy))) (s (id ?j) (st ?x&:(show ?j ?x))) => (printout t "r1 " ?i " " ?j crlf))
(defrule r2 (s (id ?i)) (not (s (id ?i) (st busy))) (exists (s (st ?y&:(show ?i ?y)))) => (printout t "r2 " ?i crlf))
(reset)
(modify 1 (st idle))
(agenda)
(run)
(exit)
