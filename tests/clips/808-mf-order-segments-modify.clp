; The order of activations from segmented matches of one fact: several patterns of
; one template with two, three and four multifield variables (sharing leading
; nodes or not), predicates between segments, joins on variables bound inside
; segments, and facts modified and retracted while the activations wait; all rules
; of one salience, so the agenda's order is the network's order.
(deftemplate cell (slot id) (multislot r) (multislot s))
(watch activations)
(defrule two (cell (id ?i) (r $?p ?v $?f)) => (printout t "two " ?i " " ?v " p=" $?p crlf))
(defrule pairs (cell (id ?i) (r $?p ?a $?m ?b $?f)) =>
  (printout t "pairs " ?i " " ?a " " ?b " m=" $?m crlf))
(defrule pairs-gt (cell (id ?i) (r $?p ?a $?m ?b&:(> ?a ?b) $?f)) =>
  (printout t "pairs-gt " ?i " " ?a ">" ?b crlf))
(defrule tail (cell (id ?i) (r ?h $?m ?l)) => (printout t "tail " ?i " " ?h " " ?l crlf))
(defrule both (cell (id ?i) (r $? ?x $?) (s $?q ?x $?)) =>
  (printout t "both " ?i " " ?x " q=" $?q crlf))
(defrule three (cell (id ?i) (r $?a ?x $?b ?y $?c ?z $?d)) =>
  (printout t "three " ?i " " ?x ?y ?z crlf))
(assert (cell (id 1) (r 3 1 2) (s 2 3)))
(defrule join-val (cell (id ?i) (r $? ?v $?)) (cell (id ?j&~?i) (s $?k ?v $?)) =>
  (printout t "join-val " ?i " " ?j " " ?v " k=" $?k crlf))
(defrule uses-s (cell (s $?u ?w $?z)) => (printout t "uses-s " ?w " u=" $?u crlf))
(assert (cell (id 2) (r 1 2) (s 1 3 2)))
(defrule first-fire (declare (salience 10)) ?c <- (cell (id 1) (r ?h $?rest)) =>
  (printout t "modify 1" crlf)
  (modify ?c (id 4) (r $?rest ?h 4)))
(run 1)
(agenda)
(bind ?x (assert (cell (id 3) (r 2 2) (s))))
(retract 2)
(agenda)
(run)
(exit)
