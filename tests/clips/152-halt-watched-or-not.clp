; (halt) ends the run after the rule's remaining actions; it names the halted rule
; ([PRCCODE4]) only while rules are watched
(defrule stop (go ?n) => (printout t "halting " ?n crlf) (halt) (printout t "the rest of the actions run" crlf))
(assert (go 1))
(run)
(printout t "after the unwatched halt" crlf)
(watch rules)
(assert (go 2))
(run)
(unwatch rules)
(watch facts)
(assert (go 3))
(run)
(exit)
