; An `or` of equalities whose alternatives are fields of an earlier ordered fact
; (`(triple ?a ?b ?c)`, or a multislot's elements at fixed offsets): the host
; reads them as it reads plain slots and looks up one bucket per alternative,
; keyed (a row) and not keyed, in a positive join and in a `not`. Same matches
; and firing order as CLIPS: alternatives interleaved in memory, equal
; alternatives, an integer against a float, an element after a multifield
; variable (offset not fixed: no lookup), cells retracted and modified while
; the probes wait.
(deftemplate cell (slot row) (slot col) (slot v))
(deftemplate box (multislot m))
(deffacts cells
  (cell (row 1) (col 1) (v 1))
  (cell (row 1) (col 2) (v 2))
  (cell (row 2) (col 1) (v 3))
  (cell (row 1) (col 3) (v 3))
  (cell (row 1) (col 4) (v 1.0))
  (cell (row 1) (col 5) (v 2))
  (cell (row 2) (col 2) (v 1))
  (cell (row 1) (col 6) (v x)))
(defrule keyed
  (triple ?a ?b ?c)
  (row ?r)
  (cell (row ?r) (v ?a|?b|?c) (col ?k))
  =>
  (printout t "keyed " ?r " " ?a "|" ?b "|" ?c " -> " ?k crlf))
(defrule unkeyed
  (pair ?a ?b)
  (cell (v ?a|?b) (row ?r) (col ?k))
  =>
  (printout t "unkeyed " ?a "|" ?b " -> " ?r "/" ?k crlf))
(defrule none-in-row
  (triple ?a ?b ?c)
  (row ?r)
  (not (cell (row ?r) (v ?a|?b|?c)))
  =>
  (printout t "none " ?r " " ?a "|" ?b "|" ?c crlf))
(defrule box-elems
  (box (m ?x ?y))
  (cell (row 1) (v ?x|?y) (col ?k))
  =>
  (printout t "box " ?x " " ?y " -> " ?k crlf))
(defrule after-multi
  (box (m $? ?x ?y))
  (cell (row 2) (v ?x|?y) (col ?k))
  =>
  (printout t "after-multi " ?x " " ?y " -> " ?k crlf))
(reset)
(assert (row 1) (row 2) (row 3))
(assert (triple 1 2 9))
(run)
(assert (triple 3 3 3))
(run)
(assert (triple 1.0 x 7))
(run)
(assert (pair 3 1))
(assert (pair 2 2))
(run)
(assert (box (m 1 3)))
(assert (box (m 9 9 1 3)))
(run)
(retract 4)
(assert (triple 3 7 8))
(run)
(modify 6 (v 7))
(assert (triple 7 8 9))
(run)
(retract 8)
(modify 2 (v 9))
(run)
(exit)
