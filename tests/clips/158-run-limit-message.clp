; CLIPS 6.30 counts a run's limit down per firing and prints "rule firing limit
; reached" when what is left equals what fired: (run 0), and a run that fires exactly
; half its limit before the agenda empties; not when the limit is used up
(watch rules)
(defrule a (x ?n&:(< ?n 3)) => (assert (x (+ ?n 1))))
(assert (x 0))
(run 6)
(assert (x 10))
(run 0)
(reset)
(assert (x 1))
(run 4)
(reset)
(assert (x 0))
(run 2)
(run 1)
(run 2)
(run)
(exit)
