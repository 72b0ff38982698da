; A retract that unblocks a not: a test CE after it reads the slots of the remaining
; facts only; an exists and two more patterns of the same template after it; the same
; through a modify's retract.
(watch rules)
(watch activations)
(deftemplate t (slot id) (slot v))
(deffunction show (?a ?b) (printout t "test " ?a " " ?b crlf) TRUE)
(deffacts start (t (id 1) (v block)) (t (id 2) (v 3)) (t (id 3) (v 4)))
(defrule r1 (t (id ?i)) (not (t (v block))) (t (id ?j) (v ?w)) (test (show ?i ?w)) => (printout t "r1 " ?i " " ?j crlf))
(defrule r2 (t (id ?i)) (not (t (v block))) (exists (t (id ?j&~?i) (v ?w&:(show ?i ?w)))) => (printout t "r2 " ?i crlf))
(defrule r3 (not (t (v block))) (t (id ?j) (v ?w)) (t (id ?k&:(> ?k ?j)) (v ?z)) (test (show ?w ?z)) => (printout t "r3 " ?j " " ?k crlf))
(reset)
(retract 1)
(agenda)
(run)
(reset)
(modify 1 (v 7))
(agenda)
(exit)
