; Keyed joins with `?a | ?b` on another slot over memories large enough that the
; host's token index grows (more than 32,768 tokens: four per cell) while the matches are in its
; key-and-slot buckets: lookups after the growth find the matches indexed before
; and after it, in memory order, for positive and `not` patterns, also after
; retracts and modifies.
(deftemplate cell (slot row) (slot col) (slot n))
(deftemplate probe (slot id) (slot row) (slot a) (slot b) (slot show))
(defglobal ?*hits* = 0 ?*sum* = 0 ?*free* = 0)
(defrule hit
  (probe (id ?i) (row ?r) (a ?a) (b ?b) (show ?s))
  (cell (row ?r) (col ?a|?b) (n ?n))
  =>
  (if ?s then (printout t "hit " ?i " " ?n crlf))
  (bind ?*hits* (+ ?*hits* 1))
  (bind ?*sum* (mod (+ ?*sum* (* ?i ?n)) 1000003)))
(defrule free
  (probe (id ?i) (row ?r) (a ?a) (b ?b))
  (not (cell (row ?r) (col ?b|?a) (n ?n&:(> ?n 0))))
  =>
  (printout t "free " ?i crlf)
  (bind ?*free* (+ ?*free* 1)))
(defrule some
  (probe (id ?i) (row ?r) (a ?a) (b ?b) (show TRUE))
  (exists (cell (row ?r) (col ?a|?b) (n ?n&:(> ?n -1))))
  =>
  (printout t "some " ?i crlf))
(defrule hit-odd
  (probe (id ?i) (row ?r) (a ?a) (b ?b) (show TRUE))
  (cell (row ?r) (col ?a|?b) (n ?n&:(> ?n -2)))
  =>
  (bind ?*sum* (mod (+ ?*sum* ?n) 1000003)))
(reset)
(assert (probe (id 1) (row 3) (a 10) (b 11) (show TRUE)))
(loop-for-count (?i 1 8500)
  (assert (cell (row (mod ?i 10)) (col (mod (* ?i 7) 25)) (n ?i))))
(run)
(printout t "hits " ?*hits* " sum " ?*sum* " free " ?*free* crlf)
(assert (probe (id 2) (row 4) (a 3) (b 24) (show TRUE)))
(assert (probe (id 3) (row 4) (a 3) (b 77) (show FALSE)))
(assert (probe (id 4) (row 5) (a 80) (b 77) (show FALSE)))
(loop-for-count (?i 5 104)
  (assert (probe (id ?i) (row (mod ?i 10)) (a (mod ?i 25)) (b (mod (* ?i 3) 30)) (show FALSE))))
(run)
(printout t "hits " ?*hits* " sum " ?*sum* " free " ?*free* crlf)
(do-for-all-facts ((?f cell)) (= (mod ?f:n 3) 0) (retract ?f))
(do-for-all-facts ((?f cell)) (and (= ?f:row 4) (= ?f:col 8)) (modify ?f (col 30)))
(do-for-all-facts ((?f cell)) (and (= ?f:row 5) (< ?f:n 200) (<> ?f:col 77)) (modify ?f (col 77)))
(assert (probe (id 200) (row 4) (a 8) (b 30) (show TRUE)))
(assert (probe (id 201) (row 4) (a 8) (b 31) (show TRUE)))
(run)
(printout t "hits " ?*hits* " sum " ?*sum* " free " ?*free* crlf)
(do-for-all-facts ((?f cell)) (and (= ?f:row 5) (= ?f:col 77)) (retract ?f))
(run)
(printout t "hits " ?*hits* " sum " ?*sum* " free " ?*free* crlf)
(exit)
