; expect: 3:13 expected robotino-agent implements
; lacks: f-2     (b)
(defrule r (logical (a)) => (assert (b)))
(assert (a))
(run)
(retract 1)
(facts)
(exit)
