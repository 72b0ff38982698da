; Logical support a rule's copy of a shared join's partial match gives (its logical CEs
; end there): on a retract it goes at that copy's place among the alpha match's
; children, before what an older successor's partial matches supported.
(deftemplate a (slot y))
(defrule r1 (logical (a (y ?v0))) (a (y ?v1)) => (assert (s1 ?v0 ?v1)))
(defrule r2 (logical (a (y ?v0)) (a (y ?v1)))  (test (<= ?v0 ?v1)) => (assert (s2 ?v0 ?v1)))
(assert (a (y 3)))
(watch facts)
(watch activations)
(retract 1)
(assert (a (y 3)))
(run)
(retract 2)
(exit)
