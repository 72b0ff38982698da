; Redefining a rule whose first join the new definition shares: CLIPS removes the old
; rule first, so that join is built again and primed oldest fact first; we keep the
; shared join and its memory, whose order (newest first) orders the new activations.
(watch activations)
(deftemplate cnt (slot c))
(deftemplate ctx (slot s))
(defrule chk (cnt (c ?c)) (ctx (s ?s)) =>)
(assert (cnt (c 0)) (ctx (s go)) (cnt (c 1)))
(defrule chk (cnt (c ?c)) (not (ctx (s down))) =>)
(assert (cnt (c 2)))
(agenda)
(exit)
