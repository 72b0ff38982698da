; expect: 9:4 expected a known function name
; keeps: 12
; lacks: lost
; An undefined global read before a missing function: CLIPS reports the function (it
; resolves globals once the deffunction is read whole), so the pointer is at the call.
(deffunction kept (?a) (* ?a 3))
(deffunction lost (?a)
  (printout t ?*never-defined* crlf)
  (frobnicate ?a))
(printout t (kept 4) crlf)
(list-deffunctions)
(exit)
