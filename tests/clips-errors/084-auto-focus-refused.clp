; expect: 2:22 expected robotino-agent implements
(defrule r (declare (auto-focus TRUE)) (a) => (printout t "fired" crlf))
(assert (a))
(run)
(exit)
