; expect: 5:34 expected allowed
; keeps: green-light
; lacks: not-blue
(deftemplate light (slot color (allowed-symbols red green)))
(defrule not-blue (light (color ~blue)) => (printout t "not blue" crlf))
(defrule green-light (light (color green)) => (printout t "green" crlf))
(list-defrules)
(exit)
