; Keyed joins whose pattern also compares another slot with `?a | ?b ...`: the
; host indexes such a node's matches on the key and that slot too, and looks up
; one bucket per alternative, merged in memory order. Same matches and
; activation order as CLIPS: matches of both alternatives asserted interleaved
; (the order of their partial matches shows in the firing order), equal
; alternatives, an integer against a float, a symbol against a string, three and
; four alternatives, five (more than the index looks up), two key slots, a node
; shared with a rule without the or that gets the or after its facts came, cells
; retracted, modified and added while probes wait, and a left value that is a
; multifield (no lookup).
(deftemplate cell (slot row) (slot plane (default 0)) (slot col) (slot n))
(deftemplate probe (slot row) (slot plane (default 0)) (slot a) (slot b) (slot c) (slot d) (slot e) (multislot m))
(defglobal ?*log* = (create$))
(deffacts cells
  (cell (row 1) (col 1) (n 1))
  (cell (row 1) (col 2) (n 2))
  (cell (row 1) (col 1) (n 3))
  (cell (row 2) (col 1) (n 4))
  (cell (row 1) (col 2) (n 5))
  (cell (row 1) (col 3) (n 6))
  (cell (row 1) (col 1.0) (n 7))
  (cell (row 1) (col "x") (n 8))
  (cell (row 1) (col x) (n 9))
  (cell (row 1) (col 4) (n 10))
  (cell (row 1) (col 5) (n 11))
  (cell (row 1) (plane 1) (col 1) (n 12))
  (cell (row 1) (plane 1) (col 2) (n 13)))
(defrule two
  (probe (row ?r) (a ?a) (b ?b) (c nil))
  (cell (row ?r) (col ?a|?b) (n ?n))
  =>
  (printout t "two " ?r " " ?a "|" ?b " -> " ?n crlf))
(defrule four
  (probe (row ?r) (a ?a) (b ?b) (c ?c&~nil) (d ?d) (e nil))
  (cell (row ?r) (col ?a|?b|?c|?d) (n ?n))
  =>
  (printout t "four " ?r " " ?a "|" ?b "|" ?c "|" ?d " -> " ?n crlf))
(defrule five
  (probe (row ?r) (a ?a) (b ?b) (c ?c) (d ?d) (e ?e&~nil))
  (cell (row ?r) (col ?a|?b|?c|?d|?e) (n ?n))
  =>
  (printout t "five " ?r " -> " ?n crlf))
(defrule planes
  (probe (row ?r) (plane ?p&~0) (a ?a) (b ?b) (c ?c))
  (cell (row ?r) (plane ?p) (col ?a|?b|?c) (n ?n))
  =>
  (printout t "planes " ?r " " ?p " -> " ?n crlf))
(defrule multi
  (probe (row ?r) (m ?x ?y))
  (cell (row ?r) (col ?x|?y) (n ?n))
  =>
  (printout t "multi " ?r " " ?x " " ?y " -> " ?n crlf))
(reset)
(assert (probe (row 1) (a 1) (b 2)))
(run)
(assert (probe (row 1) (a 2) (b 2)))
(run)
(assert (probe (row 1) (a 1.0) (b "x")))
(run)
(assert (probe (row 1) (a x) (b 9)))
(run)
(assert (probe (row 1) (a 5) (b 1) (c 3) (d 4)))
(run)
(assert (probe (row 1) (a 5) (b 1) (c 3) (d 4) (e 2)))
(run)
(assert (probe (row 1) (plane 1) (a 2) (b 7) (c 1)))
(run)
(assert (probe (row 1) (m 3 1)))
(run)
; cells change while the probes wait
(do-for-all-facts ((?f cell)) (= ?f:n 3) (retract ?f))
(do-for-all-facts ((?f cell)) (= ?f:n 2) (modify ?f (col 1)))
(assert (cell (row 1) (col 2) (n 14)))
(assert (cell (row 1) (col 1) (n 15)))
(run)
(assert (probe (row 1) (a 2) (b 1) (c nil)))
(run)
; a rule without the or shares the node; the or comes after the facts
(defrule keyed-only
  (probe (row ?r) (a ?a) (b 99))
  (cell (row ?r) (n ?n))
  =>
  (printout t "keyed-only " ?r " " ?a " -> " ?n crlf))
(assert (probe (row 2) (a 1) (b 99)))
(run)
(defrule late-or
  (probe (row ?r) (a ?a) (b ?b) (c late))
  (cell (row ?r) (col ?b|?a) (n ?n))
  =>
  (printout t "late-or " ?r " " ?a "|" ?b " -> " ?n crlf))
(assert (probe (row 1) (a 1) (b 2) (c late)))
(run)
(do-for-all-facts ((?f cell)) (= ?f:n 1) (retract ?f))
(assert (cell (row 1) (col 2) (n 16)))
(assert (probe (row 1) (a 2) (b 1) (c late)))
(run)
(exit)
