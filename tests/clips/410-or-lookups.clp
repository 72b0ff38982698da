; Joins whose pattern compares a slot with `?a | ?b ...` (variables bound earlier):
; the host looks up one index bucket per alternative (merged in memory order) when
; the pattern has no other equality with an earlier variable and only error-free
; tests come before the or. Same matches, activation order and error reports as a
; full scan:
; alternatives with equal values (a fact matches once), facts asserted in mixed
; order, retraction and modify, a negated pattern, a node shared with an earlier
; rule whose memory is already full, an error-reporting test before the or, an
; integer against a float, ordered-fact alternatives, five alternatives.
(deftemplate cell (slot id) (slot v) (slot row) (slot n))
(deftemplate pick (slot a) (slot b) (slot c) (slot row))
(deffacts start
  (cell (id 3) (v 1) (row 1) (n 1))
  (cell (id 1) (v 2) (row 2) (n 2))
  (cell (id 2) (v 3) (row 1) (n 3))
  (cell (id 1) (v abc) (row 1) (n 4))
  (cell (id 3) (v 5) (row 2) (n 5))
  (cell (id 1.0) (v 6) (row 1) (n 6))
  (cell (id x) (v 7) (row 1) (n 7))
  (cell (id 2) (v 8) (row 2) (n 8))
  (tri 3 x 1))
(defrule plain-cell
  (cell (id ?id) (n ?n))
  =>
  (printout t "plain-cell " ?id " " ?n crlf))
(reset)
(watch rules)
(run)
(defrule two-ways
  (pick (a ?a) (b ?b))
  (cell (id ?id&?a|?b) (n ?n))
  =>
  (printout t "two-ways " ?a " " ?b " -> " ?id " " ?n crlf))
(defrule three-ways-neq-first
  (pick (a ?a) (b ?b) (c ?c))
  (cell (v ?v&~?a&~?b) (id ?id&?a|?b|?c) (n ?n))
  =>
  (printout t "three-ways " ?a " " ?b " " ?c " -> " ?id " " ?v " " ?n crlf))
(defrule with-row
  (pick (a ?a) (b ?b) (row ?r))
  (cell (row ?r) (id ?a|?b) (n ?n))
  =>
  (printout t "with-row " ?r " -> " ?n crlf))
(defrule error-first
  (pick (a ?a) (b ?b))
  (cell (v ?v&:(> ?v ?b)) (id ?id&?a|?b) (n ?n))
  =>
  (printout t "error-first " ?id " " ?v " " ?n crlf))
(defrule none-of-them
  (pick (a ?a) (b ?b) (row ?r))
  (not (cell (id ?a|?b) (row ?r)))
  =>
  (printout t "none-of-them " ?a " " ?b " " ?r crlf))
(defrule ordered-ways
  (tri ?x ?y ?z)
  (cell (id ?id&?x|?y|?z) (n ?n))
  =>
  (printout t "ordered-ways " ?id " " ?n crlf))
(defrule five-ways
  (pick (a ?a) (b ?b) (c ?c) (row ?r))
  (tri ?x ?y ?z)
  (cell (id ?id&?a|?b|?c|?r|?x) (n ?n&:(> ?n 6)))
  =>
  (printout t "five-ways " ?id " " ?n crlf))
(assert (pick (a 1) (b 3) (c 1) (row 1)))
(assert (pick (a 2) (b 2) (c x) (row 2)))
(assert (pick (a 1.0) (b 9) (c 9) (row 3)))
(run)
(assert (cell (id 2) (v 9) (row 1) (n 9)))
(assert (cell (id 3) (v 10) (row 3) (n 10)))
(run)
(do-for-all-facts ((?f cell)) (or (= ?f:n 1) (= ?f:n 8)) (retract ?f))
(assert (pick (a 3) (b 1) (c 2) (row 2)))
(run)
(do-for-all-facts ((?f cell)) (= ?f:n 5) (modify ?f (id 2) (n 11)))
(assert (pick (a 3) (b 3) (c 3) (row 1)))
(run)
(facts)
(exit)
