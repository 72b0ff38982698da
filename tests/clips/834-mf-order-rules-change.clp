; The order of multifield segmentation activations while rules come and go: patterns
; with several $? on one template, rules removed and others defined (other patterns,
; other choice positions), facts asserted after each change, and a (clear) before the
; same rules come back in another order.
(watch activations)
(defrule a1 (v $?p ?x $?m ?y&:(> ?x ?y) $?f) => (printout t "a1 " ?x ">" ?y " p=" $?p crlf))
(defrule a2 (v ?k $?p ?x $?f) => (printout t "a2 " ?k " " ?x " p=" $?p crlf))
(assert (v 3 1 2))
(undefrule a2)
(defrule a3 (v $?p ?x&:(evenp ?x) $?m ?y $?f) => (printout t "a3 " ?x " " ?y " m=" $?m crlf))
(assert (v 4 1 6))
(undefrule a3)
(defrule a4 (v $? ?x $?) (v $?p ?x ?y $?) => (printout t "a4 " ?x " " ?y crlf))
(assert (v 2 2 8))
(run)
(clear)
(watch activations)
(defrule a2 (v ?k $?p ?x $?f) => (printout t "a2 " ?k " " ?x " p=" $?p crlf))
(defrule a1 (v $?p ?x $?m ?y&:(> ?x ?y) $?f) => (printout t "a1 " ?x ">" ?y " p=" $?p crlf))
(assert (v 5 4 3 2))
(run)
(exit)
