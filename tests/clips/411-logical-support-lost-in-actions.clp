; logical: a rule's logical partial match goes during its own actions. When it goes
; with the fact of the logical group's last pattern (CLIPS unlinks that partial match
; from its parents) the actions assert nothing more; when it goes as a descendant (a
; fact of an earlier pattern), or its not is blocked, or its exists loses its last
; match, the actions go on asserting new facts, without support (unconditional).
(deftemplate d (slot id) (slot k))
(deftemplate st (slot s))
(defrule first-of-two (logical ?a <- (a ?x) (b ?x)) => (retract ?a) (assert (d (id 1) (k ?x))) (assert (u 1)))
(defrule last-of-two (logical (a2 ?x) ?b <- (b2 ?x)) => (retract ?b) (assert (d (id 2) (k ?x))))
(defrule modified (logical ?p <- (p ?x)) (q) => (duplicate ?p) (assert (d (id 3) (k ?x))) (retract ?p) (assert (d (id 4) (k ?x))))
(defrule blocked (logical (go) (not (st (s on)))) ?s <- (st (s off)) => (assert (d (id 5) (k s))) (modify ?s (s on)) (assert (d (id 9) (k s))) (assert (u 1)) (assert (d (id 5) (k s))))
(defrule exists-lost (logical (go2) (exists (e ?))) ?e <- (e 1) => (retract ?e) (assert (d (id 6) (k e))))
(defrule exists-lost2 (logical (exists (e2 ?)) (go3)) ?e <- (e2 1) => (retract ?e) (assert (d (id 7) (k e))) (assert (d (id 8) (k e))))
(watch facts)
(watch rules)
(reset)
(assert (u 1) (a 1) (b 1) (a2 2) (b2 2) (q) (p 3) (go) (go2) (e 1) (go3) (e2 1) (st (s off)))
(run 20)
(facts)
(dependencies 17)
(dependencies 16)
(dependents 8)
(retract 3 5 7 9 11)
(facts)
(exit)
