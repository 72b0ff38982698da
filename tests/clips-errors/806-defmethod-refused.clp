; expect: 5:2 expected robotino-agent implements
; keeps: 6
; a generic function's method: refused by name ([NOTIMPL1]), the program going on
(deffunction twice (?x) (* 2 ?x))
(defmethod area ((?r NUMBER)) (* ?r ?r))
(printout t (twice 3) crlf)
(exit)
