; join tests of fields bound after multifields, at the edges of their compiled
; form: a non-number compared with > (the evaluator reports the error), nine
; places of segment fields in one test CE (one more than a plan holds), five
; multifields in one slot (marks 0-3), patterns beyond the eighth, constants,
; arithmetic of two segment fields, fields after the slot's last multifield
(deftemplate row (slot id) (multislot v))

; a symbol among the numbers: > reports, the join takes it as false
(defrule bigger
  (row (id e1) (v $? ?x $?))
  (row (id e2) (v $? ?y&:(> ?y ?x) $?))
  =>
  (printout t "bigger " ?x " " ?y crlf))

; segment fields at nine different places in one test CE
(defrule nine
  (row (id n) (v $? ?a $? ?b $? ?c $?))
  (row (id m) (v $? ?d ?e ?f $? ?g ?h ?i ?j))
  (test (and (< ?a ?d) (< ?b ?e) (< ?c ?f) (<= ?a ?g) (<= ?b ?h) (<= ?c ?i) (neq ?a ?b ?c ?j)))
  =>
  (printout t "nine " ?a ?b ?c " " ?d ?e ?f ?g ?h ?i ?j crlf))

; five multifields in one slot (the most a pattern holds): a field after the fourth
(defrule five
  (row (id f) (v $? ?p $? ?q $? ?r $? ?s $?))
  (row (id g) (v ?r|?s $?))
  =>
  (printout t "five " ?p ?q ?r ?s crlf))

; constants and arithmetic of two segment fields, fields after the last multifield
(defrule arith
  (row (id c) (v x $? ?u ?w))
  (row (id d) (v $?pre ?k&:(= ?k (+ ?u ?w))&~7 $?post ?z&:(eq ?z (* ?u 2))))
  =>
  (printout t "arith " ?u " " ?w " " ?k " " ?z " " (length$ ?pre) " " (length$ ?post) crlf))

; sub-string of a segment field, string compare
(defrule cut
  (row (id s) (v $? ?str $?))
  (row (id t) (v $? ?o&:(eq (sub-string 1 2 ?str) ?o) $?))
  =>
  (printout t "cut " ?str " " ?o crlf))

; the tested fields' patterns beyond the eighth
(defrule deep
  (row (id a) (v ?a1 $?))
  (row (id b) (v ?b1 $?))
  (row (id c) (v ?c1 $?))
  (row (id d) (v ?d1 $?))
  (row (id s) (v ?s1 $?))
  (row (id t) (v ?t1 $?))
  (row (id n) (v ?n1 $?))
  (row (id m) (v ?m1 $?))
  (row (id f) (v $? ?f9 ?f10))
  (row (id g) (v $? ?g9&:(> ?g9 ?f9) $? ?g10&~?f10))
  =>
  (printout t "deep " ?f9 " " ?f10 " " ?g9 " " ?g10 crlf))

(deffacts start
  (row (id a) (v 1 5 x))
  (row (id b) (v 3 y 6))
  (row (id n) (v 1 2 3))
  (row (id m) (v 2 3 4 5 6 7 8))
  (row (id f) (v 1 2 3 4 5 6))
  (row (id g) (v 5 0))
  (row (id c) (v x 1 2 3))
  (row (id d) (v 4 5 6 7 4))
  (row (id s) (v "abc" "xyz"))
  (row (id t) (v "ab" "xy" "ax")))

(reset)
(run)
(printout t "--- modify" crlf)
(do-for-fact ((?r row)) (eq ?r:id g) (modify ?r (v 6 1 9)))
(do-for-fact ((?r row)) (eq ?r:id d) (modify ?r (v 9 8 5 9 4)))
(do-for-fact ((?r row)) (eq ?r:id f) (modify ?r (v 7 8 9 1 2)))
(run)
(printout t "--- errors" crlf)
(assert (row (id e1) (v 1 5 x)))
(assert (row (id e2) (v 3 y 6)))
(run)
(do-for-fact ((?r row)) (eq ?r:id e1) (modify ?r (v 2 4)))
(run)
(exit)
