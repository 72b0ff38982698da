; join tests of fields bound after multifields (read by the multifield marks):
; or-tests (?a|?b), ~?a&~?b and =(...) / :(...) on segment elements in not,
; exists and plain joins, fields after the slot's last multifield, between
; multifields, after two of them; facts modified and retracted between runs
(deftemplate cell (slot id) (slot row) (multislot vals))
(deftemplate pick (slot id) (multislot pair))

; not: no other cell of the row holds ?a or ?b (hidden pair shape)
(defrule hidden-pair
  (cell (id ?i) (row ?r) (vals $? ?a $? ?b $?))
  (cell (id ?j&:(< ?i ?j)) (row ?r) (vals $? ?a $? ?b $?))
  (not (cell (id ~?i&~?j) (row ?r) (vals $? ?a|?b $?)))
  =>
  (printout t "hidden-pair " ?i " " ?j " " ?a " " ?b crlf))

; exists: some cell holds the successor of ?a after a multifield
(defrule succ-exists
  (cell (id ?i) (vals $? ?a))
  (exists (cell (id ~?i) (vals $? =(+ ?a 1) $?)))
  =>
  (printout t "succ-exists " ?i " " ?a crlf))

; plain join: a field neither of two segment-bound values, after two multifields
(defrule other-than
  (pick (id ?p) (pair ?x $? ?y))
  (cell (id ?i) (vals $? ?z&~?x&~?y $? ?w&:(> ?w ?z)))
  =>
  (printout t "other-than " ?p " " ?i " " ?z " " ?w crlf))

; ordered facts: three fields after a multifield, or-tested in a not
(defrule trio-free
  (trio $? ?t1 ?t2 ?t3&:(= (+ ?t1 2) ?t3) $?)
  (not (used $? ?t1|?t2|?t3 $?))
  =>
  (printout t "trio-free " ?t1 " " ?t2 " " ?t3 crlf))

; a field between singles and multifields on both sides of the test
(defrule between
  (pick (id ?p) (pair a $?m ?u b $? ?v))
  (cell (id ?i) (vals ?f $? ?u|?v $?rest ?l))
  =>
  (printout t "between " ?p " " ?i " " ?u " " ?v " " ?f " " ?l crlf))

; join predicates on fields between multifields and after the last one
(defrule join-pred
  (trio $? ?t1 ?t2 $?)
  (used $? ?u&:(> ?u ?t2) $? ?k&~?t1&:(<> ?k ?u))
  =>
  (printout t "join-pred " ?t1 " " ?t2 " " ?u " " ?k crlf))

(deffacts start
  (cell (id 1) (row 1) (vals 1 2 7))
  (cell (id 2) (row 1) (vals 1 2 5))
  (cell (id 3) (row 1) (vals 3 5 9))
  (cell (id 4) (row 2) (vals 4 8))
  (cell (id 5) (row 2) (vals 4 6 8))
  (cell (id 6) (row 2) (vals 1 9))
  (pick (id p1) (pair 2 x 7))
  (pick (id p2) (pair a 1 4 b z 8))
  (trio 1 2 3 4 5)
  (trio 7 8 9)
  (used 0 4 9))

(reset)
(run)
(printout t "--- modify" crlf)
(do-for-fact ((?c cell)) (eq ?c:id 3) (modify ?c (vals 3 9)))
(do-for-fact ((?c cell)) (eq ?c:id 5) (modify ?c (vals 6 2)))
(do-for-fact ((?u used)) TRUE (retract ?u))
(assert (used 3 7))
(run)
(printout t "--- retract" crlf)
(do-for-fact ((?c cell)) (eq ?c:id 6) (retract ?c))
(do-for-fact ((?p pick)) (eq ?p:id p1) (modify ?p (pair 1 2 8 9)))
(assert (cell (id 7) (row 1) (vals 2 a 4 b 8 6)))
(run)
(printout t "--- more" crlf)
(do-for-all-facts ((?c cell)) (and (eq ?c:row 1) (neq (nth$ 2 ?c:vals) 8))
  (modify ?c (vals 1 8 ?c:id)))
(assert (used 5 6 7 8 9))
(run)
(exit)
