; A run-time error inside nested deffunctions called from a rule: the error, then each
; deffunction frame and the rule, in CLIPS's order (the error's own text is left to the
; differential suite; CLIPS's transcript is 002-error-inside-deffunctions.clips-out).
; prints: [PRCCODE4] Execution halted during the actions of deffunction inner.
; prints: [PRCCODE4] Execution halted during the actions of deffunction outer.
; prints: [PRCCODE4] Execution halted during the actions of defrule divide.
; prints: 3
(deffunction inner (?x) (/ ?x 0))
(deffunction outer (?x) (inner ?x))
(defrule divide => (outer 1))
(reset)
(run)
(printout t (+ 1 2) crlf)
(exit)
