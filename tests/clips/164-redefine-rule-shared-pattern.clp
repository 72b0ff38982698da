; Redefining a rule while facts exist: the new rule shares the old one's first join and
; the alpha node of its last pattern, whose only successor was the old rule's last join.
; Removing the old rule must not empty that node: the new rule is primed with the facts
; there and matches facts asserted later.
(watch activations)
(deftemplate cnt (slot c))
(deftemplate ctx (slot s))
(defrule chk (cnt (c ?c)) (ctx (s ?s)) =>)
(assert (cnt (c 0)) (ctx (s go)))
(defrule chk (cnt (c ?c)) (ctx (s ?s)) (test (eq ?c 0)) =>)
(assert (cnt (c 1)) (ctx (s stop)))
(agenda)
(defrule chk (cnt (c ?c)) (ctx (s ?s&~go)) =>)
(assert (ctx (s up)))
(agenda)
(exit)
