; Rules primed below a partial match they share with older rules, under not and
; exists, and rules sharing two joins: when a fact goes, the copies priming made go
; first (the latest primed first), then the older rules' in their order.
(deftemplate it (slot id) (slot w))
(deftemplate k (slot v))
(defrule n1 (it (id ?i)) (not (k (v ?i))) =>)
(defrule e1 (it (id ?i)) (exists (k (v 9))) =>)
(defrule p1 (it (id ?i)) (k (v ?v)) (it (w ?v)) =>)
(assert (it (id 1) (w 2)))
(assert (k (v 2)))
(assert (k (v 9)))
(watch activations)
(defrule n2 (it (id ?i)) (not (k (v ?i))) (k (v 9)) =>)
(defrule e2 (it (id ?i)) (exists (k (v 9))) (k (v ?x)) =>)
(defrule p2 (it (id ?i)) (k (v ?v)) (it (w ?v)) (k (v 9)) =>)
(defrule p3 (it (id ?i)) (k (v ?v)) =>)
(retract 3)
(retract 1)
(exit)
