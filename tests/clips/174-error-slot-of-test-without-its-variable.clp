; A pattern test that fails with an error is reported at the slot whose constraint holds
; it, even when the test does not use that slot's variable (the test's root names its
; slot when it reads another field first, or none).
(deftemplate it (slot id) (slot w))
(defglobal ?*s* = a)
(defrule a (it (id 9) (w ?w&:(progn (+ ?*s* 1) TRUE))) =>)
(assert (it (id 9) (w q)))
(exit)
