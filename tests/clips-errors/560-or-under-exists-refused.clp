; expect: 3:20 expected robotino-agent implements
; keeps: ok
(defrule r (x ?v) (exists (or (a ?v) (and (b ?v) (c ?v)))) => (printout t ?v crlf))
(printout t ok crlf)
(exit)
