; expect: 3:8 expected robotino-agent implements
; keeps: 2
(watch globals)
(defglobal ?*g* = 1)
(bind ?*g* 2)
(printout t ?*g* crlf)
(exit)
