; expect: 3:20 expected robotino-agent implements
; keeps: ok
(defrule r (x ?v) (exists (or (a ?v) (b ?v))) => (printout t ?v crlf))
(printout t ok crlf)
(exit)
