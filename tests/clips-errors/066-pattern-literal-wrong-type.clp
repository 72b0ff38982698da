; expect: 4:27 expected type
; lacks: slow
(deftemplate counter (slot n (type INTEGER)))
(defrule slow (counter (n slow)) => (printout t "slow" crlf))
(list-defrules)
(exit)
