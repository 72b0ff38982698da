; A modify's new fact meets a join test that fails (`>` of a symbol) on a fact that the
; next modify of the same actions retracts: CLIPS builds the new fact's matches first,
; so the error is reported and the actions stop; no retract may overtake a test that
; can fail, or the error would be lost. Without (watch facts), which keeps the eager
; order anyway.
(watch rules)
(deftemplate cnt (slot c))
(deftemplate ctx (slot s))
(deffacts d (cnt (c 0)) (ctx (s go)))
(defrule step ?x <- (ctx (s go)) ?n <- (cnt (c 0)) => (modify ?n (c 1)) (modify ?x (s stop)))
(defrule chk (cnt (c ?c)) (ctx (s ?s)) (test (or (neq ?s go) (< ?c 1) (> ?s ?c))) =>)
(reset)
(run)
(facts)
; the same with `eq` tests only, which cannot fail: both modifies complete
(defrule chk (cnt (c ?c)) (ctx (s ?s)) (test (or (neq ?s go) (eq ?c 0))) =>)
(reset)
(run)
(facts)
(exit)
