; expect: 2:12 expected robotino-agent implements
(defmodule SENSE (export ?ALL))
(defrule ok (a ?x) => (printout t "ok " ?x crlf))
(assert (a 1))
(run)
(exit)
