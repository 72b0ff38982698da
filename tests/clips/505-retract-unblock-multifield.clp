; A retract that unblocks a not, the dying fact matching the same alpha node several
; times (multifield segmentations): none of its matches is seen by the joins below.
(watch rules)
(watch activations)
(deffunction show (?a ?b) (printout t "join " ?a " " ?b crlf) TRUE)
(deffacts start (lst a b) (lst c) (go))
(defrule r1 (go) (not (lst $? b $?)) (lst $?x ?y $?z&:(show ?y (length$ ?z))) => (printout t "r1 " ?y crlf))
(defrule r2 (lst $?x ?y $?) (not (lst $? b)) (lst $? ?w&:(show ?w ?y) $?) => (printout t "r2 " ?y " " ?w crlf))
(reset)
(retract 1)
(agenda)
(run)
(exit)
