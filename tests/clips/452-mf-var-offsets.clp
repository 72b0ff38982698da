; Variables bound after several multifield wildcards: their offset is the singles
; before them plus the lengths of the multifields before them (the last multifield's
; length is what the others leave), read both in a pattern's predicate and in actions.
(deftemplate bag (slot id) (multislot items) (slot tag))
(deffacts data
  (v a 1 2 4 5 2 7)
  (v b 3 9 1)
  (bag (id 1) (items 5 3 8 1 9) (tag t1))
  (bag (id 2) (items 2 2) (tag t2)))
(defrule sort-step
  ?f <- (v ?n $?p ?x $?m ?y&:(> ?x ?y) $?e)
  =>
  (retract ?f)
  (printout t ?n " swap " ?x " " ?y " p=" $?p " m=" $?m " e=" $?e crlf)
  (assert (v ?n $?p ?y $?m ?x $?e)))
(defrule last-after-all (declare (salience -10))
  (v ?n $?a ?k $?b ?z&:(numberp ?z))
  (test (= (length$ $?b) 0))
  =>
  (printout t ?n " k=" ?k " z=" ?z " a=" $?a crlf))
(defrule bag-split (declare (salience -20))
  (bag (id ?i) (items ?first $?mid ?q&:(> ?q 4) $?rest) (tag ?t))
  =>
  (printout t ?i " " ?t " first=" ?first " mid=" $?mid " q=" ?q " rest=" $?rest crlf))
(defrule bag-three (declare (salience -30))
  (bag (id ?i) (items $?a ?x $?b ?y $?c ?z&:(< ?x ?y ?z)))
  =>
  (printout t ?i " up " ?x ?y ?z " a=" $?a " b=" $?b " c=" $?c crlf))
(reset)
(run)
(facts)
(exit)
