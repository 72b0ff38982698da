; expect: 5:2 expected robotino-agent implements
; keeps: 8
; a class of CLIPS's object system (COOL): refused by name ([NOTIMPL1]), the program going on
(deffunction twice (?x) (* 2 ?x))
(defclass Point (is-a USER) (slot x) (slot y))
(printout t (twice 4) crlf)
(exit)
