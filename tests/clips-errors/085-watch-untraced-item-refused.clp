; expect: 3:16 expected robotino-agent implements
; keeps: 2
(watch globals g)
(defglobal ?*g* = 1)
(bind ?*g* 2)
(printout t ?*g* crlf)
(exit)
