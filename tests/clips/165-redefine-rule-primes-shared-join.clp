; Redefining a rule whose first join only the old definition used: CLIPS removes the
; old rule first, so that join is built again and primed oldest fact first, not shared
; with its memory (newest first), whose order would order the new activations.
(watch activations)
(deftemplate cnt (slot c))
(deftemplate ctx (slot s))
(defrule chk (cnt (c ?c)) (ctx (s ?s)) =>)
(assert (cnt (c 0)) (ctx (s go)) (cnt (c 1)))
(defrule chk (cnt (c ?c)) (not (ctx (s down))) =>)
(assert (cnt (c 2)))
(agenda)
(exit)
