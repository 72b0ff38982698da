; An error in the pattern network while reset asserts the deffacts halts the reset: no
; further deffacts fact is asserted, in this deffacts or the next. A construct or a new
; command is not halted by an earlier one's error.
(deftemplate it (slot id) (slot w))
(defrule p (it (w ?w&:(> ?w 1))) =>)
(defrule q (it (w ?w&:(progn TRUE))) =>)
(deffacts d (it (id 1) (w q)) (it (id 2) (w 5)))
(deffacts e (it (id 8) (w 5)))
(watch activations)
(reset)
(facts)
(agenda)
(defrule r (it (id ?i&:(progn TRUE))) =>)
(agenda)
(undefrule r)
(undeffacts d)
(reset)
(facts)
(exit)
