; expect: 4:31 expected global
; keeps: 1
(defglobal ?*known* = 1)
(defrule r (a) => (printout t ?*nope* crlf))
?*known*
(exit)
