; expect: 3:18 expected robotino-agent implements
; keeps: 2
(watch instances USER)
(defglobal ?*g* = 1)
(bind ?*g* 2)
(printout t ?*g* crlf)
(exit)
