; join tests that read fields bound after multifields (marked plans), where the
; slots compared lie before the template's first multislot (read at a fixed offset
; in the fact), after it (found by a walk over the slots), or in a second
; multislot; two templates whose same slot numbers lie at different places; not,
; exists and plain joins; facts modified and retracted between runs
(deftemplate cell (slot row) (slot col) (slot box) (multislot cands) (slot id) (multislot log))
(deftemplate mark (multislot tags) (slot row) (slot col) (multislot vals) (slot id))

; a single field of the left, a field after a multifield on the right, slots at
; fixed offsets compared (eq and neq)
(defrule row-taken
  (cell (row ?r) (col ?c) (cands ?v))
  (cell (row ?r) (col ~?c) (cands $?a ?v $?b) (id ?i))
  =>
  (printout t "row-taken " ?r " " ?c " " ?v " in " ?i crlf))

; the slot after the multislot compared (a walk), in a not
(defrule box-alone
  (cell (id ?i) (box ?x) (cands $? ?v $?))
  (not (cell (id ~?i) (box ?x) (cands $? ?v $?)))
  =>
  (printout t "box-alone " ?i " " ?v crlf))

; both fields after multifields, slots before the multislot compared (eq, neq)
(defrule row-box-only
  (cell (id ?i) (row ?r) (box ?b) (cands $?p ?v $?f&:(> (+ (length$ ?p) (length$ ?f)) 0)))
  (not (cell (row ?r) (box ~?b) (cands $?p2 ?v $?f2)))
  =>
  (printout t "row-box-only " ?i " " ?v crlf))

; another template whose row/col lie after a multislot: the same slot numbers
; are not at fixed offsets there
(defrule mark-hit
  (mark (tags $? ?t $?) (row ?r) (col ?c) (vals $? ?v $?) (id ?m))
  (cell (row ?r) (col ?c) (box ?t) (cands $? ?v $?) (id ?i))
  =>
  (printout t "mark-hit " ?m " " ?i " " ?t " " ?v crlf))

(defrule mark-miss
  (cell (row ?r) (col ?c) (cands $? ?v $?) (id ?i))
  (not (mark (row ?r) (col ~?c) (vals $? ?v $?)))
  =>
  (printout t "mark-miss " ?i " " ?v crlf))

; a field of the second multislot (after the first): exists
(defrule logged
  (cell (id ?i) (log $? ?w $?) (row ?r))
  (exists (cell (id ~?i) (row ~?r) (log $? ?w $?)))
  =>
  (printout t "logged " ?i " " ?w crlf))

(deffacts start
  (cell (row 1) (col 1) (box 1) (cands 5) (id c11) (log a))
  (cell (row 1) (col 2) (box 1) (cands 3 5 7) (id c12) (log b a))
  (cell (row 1) (col 3) (box 2) (cands 5 9) (id c13))
  (cell (row 2) (col 1) (box 1) (cands 3) (id c21) (log b))
  (cell (row 2) (col 2) (box 2) (cands 7 9) (id c22) (log c))
  (mark (tags 1 2) (row 1) (col 2) (vals 7 8) (id m1))
  (mark (tags) (row 2) (col 2) (vals 9) (id m2))
  (mark (tags 2) (row 1) (col 3) (vals 1 9) (id m3)))

(reset)
(run)
(printout t "--- modify" crlf)
(do-for-fact ((?c cell)) (eq ?c:id c12) (modify ?c (cands 3 7) (log z)))
(do-for-fact ((?m mark)) (eq ?m:id m2) (modify ?m (tags x y 1 2) (vals 9 3)))
(assert (cell (row 2) (col 3) (box 2) (cands 3 9) (id c23) (log c a)))
(run)
(printout t "--- retract" crlf)
(do-for-fact ((?c cell)) (eq ?c:id c11) (retract ?c))
(do-for-fact ((?m mark)) (eq ?m:id m1) (modify ?m (tags) (row 2) (col 3) (vals 3)))
(run)
(exit)
