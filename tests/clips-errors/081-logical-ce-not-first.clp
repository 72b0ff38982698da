; expect: 4:17 expected logical CEs must be placed first
; lacks: f-3     (b)
; a logical CE after a pattern: CLIPS's RULEPSR1, nothing defined
(defrule r (a) (logical (c)) => (assert (b)))
(assert (a))
(assert (c))
(run)
(facts)
(exit)
