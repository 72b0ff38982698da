; Several multifields in two multislots of one pattern, a segment variable joined to
; other patterns and tested under `not`, and a one-multifield slot whose fields after
; it are counted from the end with predicates on them.
(deftemplate rec (slot id) (multislot xs) (multislot ys) (slot k))
(defrule cross (rec (id ?i) (xs $?a ?x $?b) (ys $?c ?y&:(> ?y ?x) $?d) (k ?k&:(< ?k ?y)))
  => (printout t "cross " ?i " " ?x " " ?y " a=" $?a " c=" $?c crlf))
(defrule tail (rec (id ?i) (xs $?a ?p ?q&:(> ?q ?p)))
  => (printout t "tail " ?i " " ?p " " ?q " a=" $?a crlf))
(defrule head-tail (rec (id ?i) (ys ?f $?m ?l&:(< ?f ?l)))
  => (printout t "head-tail " ?i " " ?f " " ?l " m=" $?m crlf))
(defrule probe (want ?w) (rec (id ?i) (xs $?a ?w $?b))
  => (printout t "probe " ?w " in " ?i " at " (+ 1 (length$ ?a)) crlf))
(defrule absent (want ?w) (not (rec (xs $? ?w $?)))
  => (printout t "absent " ?w crlf))
(defrule pair-x (rec (id ?i) (xs $? ?x $?)) (rec (id ?j&~?i) (ys $? ?y&:(= ?y (* 2 ?x)) $?))
  => (printout t "pair-x " ?i " " ?x " " ?j crlf))
(deffacts d
  (rec (id 1) (xs 1 5 2) (ys 3 6 0) (k 2))
  (rec (id 2) (xs 4 3) (ys 8 1 10) (k 5))
  (want 5) (want 7) (want 3))
(watch activations)
(reset)
(run)
(exit)
