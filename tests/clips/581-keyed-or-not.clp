; `not` and `exists` over a keyed pattern with `?a | ?b ...` on another slot:
; the host looks up one bucket of its key-and-slot index per alternative, and when
; a blocker goes it searches on from the matches after it in memory order. Same
; activations, deactivations and firing order as CLIPS: blockers of both
; alternatives asserted interleaved and retracted one by one in several orders,
; modified into another row or column and back, equal alternatives, three
; alternatives, a blocker with two matches of one fact (multislot segmentations)
; going away, and a retract during the run.
(deftemplate blk (slot row) (slot col) (slot n) (multislot tags))
(deftemplate q (slot id) (slot row) (slot a) (slot b) (slot c))
(deffacts start
  (q (id 1) (row 1) (a 1) (b 2))
  (q (id 2) (row 1) (a 2) (b 2))
  (q (id 3) (row 2) (a 1) (b 3) (c 4))
  (q (id 4) (row 1) (a 3) (b 1)))
(defrule none
  (q (id ?i) (row ?r) (a ?a) (b ?b) (c nil))
  (not (blk (row ?r) (col ?a|?b)))
  =>
  (printout t "none " ?i crlf))
(defrule none3
  (q (id ?i) (row ?r) (a ?a) (b ?b) (c ?c&~nil))
  (not (blk (row ?r) (col ?a|?b|?c)))
  =>
  (printout t "none3 " ?i crlf))
(defrule some
  (q (id ?i) (row ?r) (a ?a) (b ?b))
  (exists (blk (row ?r) (col ?a|?b)))
  =>
  (printout t "some " ?i crlf))
(defrule tagged-none
  (q (id ?i) (row ?r) (a ?a) (b ?b))
  (not (blk (row ?r) (col ?b|?a) (tags $? t $?)))
  =>
  (printout t "tagged-none " ?i crlf))
(deffunction drop (?n)
  (do-for-all-facts ((?f blk)) (= ?f:n ?n) (retract ?f)))
(deffunction move (?n ?row ?col)
  (do-for-all-facts ((?f blk)) (= ?f:n ?n) (modify ?f (row ?row) (col ?col))))
(watch activations)
(reset)
(assert (blk (row 1) (col 1) (n 1)))
(assert (blk (row 1) (col 2) (n 2)))
(assert (blk (row 1) (col 1) (n 3)))
(assert (blk (row 2) (col 4) (n 4)))
(assert (blk (row 1) (col 2) (n 5)))
(assert (blk (row 1) (col 3) (n 6) (tags t u t)))
(assert (blk (row 2) (col 3) (n 7) (tags t t)))
(agenda)
(drop 1)
(agenda)
(drop 5)
(agenda)
(move 2 2 1)
(agenda)
(drop 3)
(agenda)
(drop 6)
(agenda)
(move 2 1 2)
(agenda)
(drop 7)
(agenda)
(drop 4)
(agenda)
(run)
(assert (blk (row 1) (col 2) (n 8) (tags t)))
(assert (blk (row 1) (col 1) (n 9) (tags t t)))
(agenda)
(drop 8)
(agenda)
(drop 2)
(agenda)
(drop 9)
(agenda)
(defrule sweep
  (declare (salience 10))
  ?f <- (blk (n ?n&:(> ?n 9)))
  =>
  (retract ?f))
(assert (blk (row 1) (col 2) (n 10)) (blk (row 1) (col 1) (n 11)) (blk (row 2) (col 3) (n 12)))
(run)
(exit)
