; expect: 2:31 expected expression
(defrule r (a) => (printout t ? crlf))
(exit)
