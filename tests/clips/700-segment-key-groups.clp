; joins keyed on variables bound inside segments (after one or two multifields),
; several joins under one shared parent (each its own index group), joined to
; plain slots, to fixed elements and to other segmented patterns; facts asserted
; in stages, modified and retracted while the memories are indexed
(deftemplate cell (slot id) (slot row) (slot col) (multislot vals))
(deftemplate tag (slot row) (slot v) (slot name))
(deftemplate lst (slot id) (multislot xs))

; three rules share their first pattern (one parent join); the second patterns
; join on ?v bound after a multifield, with another slot each
(defrule row-share
  (cell (id ?i) (row ?r) (col ?c) (vals $? ?v $?))
  (cell (id ?j&:(< ?i ?j)) (row ?r) (vals $? ?v $?))
  =>
  (printout t "row-share " ?i " " ?j " " ?v crlf))

(defrule col-share
  (cell (id ?i) (row ?r) (col ?c) (vals $? ?v $?))
  (cell (id ?j&:(< ?i ?j)) (col ?c) (vals $? ?v $?))
  =>
  (printout t "col-share " ?i " " ?j " " ?v crlf))

(defrule tag-of
  (cell (id ?i) (row ?r) (col ?c) (vals $? ?v $?))
  (tag (row ?r) (v ?v) (name ?n))
  =>
  (printout t "tag " ?n " on " ?i " " ?v crlf))

; pairs: two variables after two multifields, joined to another segmented pair
; (three rules on one first pattern again)
(defrule pair-row
  (cell (id ?i) (row ?r) (col ?c) (vals $? ?a $? ?b $?))
  (cell (id ?j&~?i) (row ?r) (vals $? ?a $? ?b $?))
  =>
  (printout t "pair-row " ?i " " ?j " " ?a " " ?b crlf))

(defrule pair-col
  (cell (id ?i) (row ?r) (col ?c) (vals $? ?a $? ?b $?))
  (cell (id ?j&~?i) (col ?c) (vals $?p ?a $?m ?b $?f&:(> (length$ ?m) 0)))
  =>
  (printout t "pair-col " ?i " " ?j " " ?a " " ?b crlf))

(defrule pair-fixed
  (cell (id ?i) (row ?r) (col ?c) (vals $? ?a $? ?b $?))
  (cell (id ?j&~?i) (vals ?a ?b))
  =>
  (printout t "pair-fixed " ?i " " ?j " " ?a " " ?b crlf))

; a variable before a multifield and one after it, joined to a list's ends
(defrule ends
  (lst (id ?l) (xs ?h $?mid ?t))
  (cell (id ?i) (vals $? ?h $? ?t))
  (cell (id ?j&~?i) (vals ?t $?))
  =>
  (printout t "ends " ?l " " ?i " " ?j " " ?h " " ?t crlf))

; a multifield variable bound in a segment compared whole
(defrule same-tail
  (lst (id ?l) (xs ?x $?rest))
  (lst (id ?m&~?l) (xs $? ?y $?rest&:(> (length$ ?rest) 0)))
  =>
  (printout t "tail " ?l " " ?m " " ?x " " ?y " " ?rest crlf))

; not and exists keyed on segment variables
(defrule lone-value
  (cell (id ?i) (row ?r) (vals $?p ?v $?f&:(> (+ (length$ ?p) (length$ ?f)) 0)))
  (not (cell (id ~?i) (row ?r) (vals $? ?v $?)))
  =>
  (printout t "lone " ?i " " ?v crlf))

(defrule shared-somewhere
  (tag (row ?r) (v ?v) (name ?n))
  (exists (cell (row ?r) (vals $? ?v $?)))
  =>
  (printout t "exists " ?n " " ?v crlf))

(deffacts start
  (cell (id 1) (row 1) (col 1) (vals 1 2 3))
  (cell (id 2) (row 1) (col 2) (vals 3 4))
  (cell (id 3) (row 2) (col 1) (vals 1 3 4))
  (tag (row 1) (v 3) (name t13))
  (lst (id 1) (xs 1 2 3)))

(reset)
(run)
(assert (cell (id 4) (row 1) (col 1) (vals 4 3 1)))
(assert (cell (id 5) (row 2) (col 2) (vals 1 4.0 4 3)))
(assert (tag (row 2) (v 4) (name t24)))
(assert (tag (row 2) (v 4.0) (name t24f)))
(assert (lst (id 2) (xs 9 2 3)))
(assert (lst (id 3) (xs 3 a 1)))
(run)
(assert (cell (id 6) (row 1) (col 2) (vals 2 3)))
(assert (cell (id 7) (row 2) (col 1) (vals 4 1)))
(run)
(do-for-fact ((?c cell)) (eq ?c:id 2) (modify ?c (vals 4 2 1)))
(run)
(do-for-fact ((?c cell)) (eq ?c:id 4) (retract ?c))
(do-for-fact ((?c cell)) (eq ?c:id 3) (modify ?c (row 1) (vals 3 9)))
(run)
(do-for-fact ((?c cell)) (eq ?c:id 1) (modify ?c (vals 9 3)))
(assert (cell (id 8) (row 1) (col 3) (vals 9 3 5 4)))
(assert (lst (id 4) (xs 4 9 3)))
(run)
(do-for-all-facts ((?t tag)) TRUE (retract ?t))
(do-for-fact ((?c cell)) (eq ?c:id 5) (retract ?c))
(assert (tag (row 1) (v 9) (name t19)))
(run)
(printout t "facts " (length$ (find-all-facts ((?c cell)) TRUE)) crlf)
(exit)
