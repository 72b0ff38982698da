; A numeric predicate on a field after several multifields meeting a symbol: the
; error is reported from the pattern network (once per failing test, as CLIPS
; evaluates it), and the tests before and after it keep their order.
(defrule gt (v $?a ?x $?b ?y&:(> ?y ?x) $?c)
  => (printout t "gt " ?x " " ?y crlf))
(assert (v 1 2 3))
(run)
(assert (v 1 x 2))
(run)
(defrule g2 (w $?a ?x&:(eq ?x k) $?b ?y&:(> ?y 0) $?c ?z&:(eq ?z stop))
  => (printout t "g2 " ?y crlf))
(assert (w k 1 zz stop))
(assert (w j 1 zz stop))
(assert (w k zz 1 stop))
(run)
(exit)
