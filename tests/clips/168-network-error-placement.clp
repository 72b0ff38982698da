; Where a failing test runs decides how CLIPS reports it. A variable bound earlier and
; equated with a field (`?w&:(> ?w 1)`, or `?i` in another field) is read from this
; fact, so the predicate is a pattern-network test ([FACTMCH1]); a `&` chain is split:
; only the equality goes to the join. A `test` after a `not` fails in the join network
; ([DRIVE1]) and the fact stays. An error lists every rule sharing the node, newest
; first. A multi-fact assert whose fact fails a test returns FALSE, a lone fact itself.
(watch activations)
(deftemplate it (slot id) (slot v) (slot w))
(deftemplate mk (slot v))
(defrule a (it (v ?i)) (it (id ?i) (w ?w&:(> ?w ?i))) =>)
(defrule c (it (v ?m)) (it (w ?z&?m&:(> ?z 1))) =>)
(defrule d (it (v ?n)) (it (w ?z&:(> ?z 1)&?n)) =>)
(defrule n (it (id ?i) (w ?w)) (not (mk (v z))) (test (> ?w 0)) => (printout t "n " ?i crlf))
(assert (it (id q) (v q) (w 1)))
(assert (it (id 1) (v 1) (w r)))
(assert (mk (v y)) (it (id 5) (v 2) (w s)))
(assert (it (id 6) (v 2) (w 3)) (it (id 7) (v 2) (w t)))
(run)
(facts)
(exit)
