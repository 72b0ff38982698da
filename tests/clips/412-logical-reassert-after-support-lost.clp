; logical: a rule whose logical partial match went during its actions (its not blocked,
; not with its own fact) asserts a fact another rule supports: CLIPS links the fact to
; the dead partial match until the firing ends, so a fact losing its other support
; meanwhile stays, unconditional; one keeping it stays supported. With the partial match
; gone with its own fact, no link: the fact goes with its support.
(deftemplate d (slot id))
(deftemplate st (slot s))
(defrule keep (logical (not (d (id 4)))) => (assert (d (id 2))) (assert (d (id 3))))
(defrule keep2 (logical (e 3)) => (assert (d (id 3))))
(defrule orphan (logical (go) (not (st (s on)))) ?s <- (st (s off)) => (modify ?s (s on)) (assert (d (id 2))) (assert (d (id 3))) (assert (d (id 4))) (printout t "orphan done" crlf))
(defrule keep-b (logical (k)) => (assert (d (id 12))))
(defrule cut (logical ?g <- (go2)) ?k <- (k) => (retract ?g) (assert (d (id 12))) (retract ?k) (printout t "cut done" crlf))
(watch facts)
(watch rules)
(reset)
(assert (e 3) (k))
(run 3)
(assert (go) (st (s off)))
(run 1)
(facts)
(dependencies 2)
(dependencies 3)
(dependents 1)
(assert (go2))
(run 1)
(facts)
(retract 1)
(facts)
(exit)
