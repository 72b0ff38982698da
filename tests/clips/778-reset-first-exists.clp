; `reset` takes back the matches of rules that start with `not` or `test` before it
; retracts the facts, but a first `exists` keeps its match until the facts go: its
; activations leave fact by fact, in the order the facts are retracted.
(deftemplate a (slot z (default 0)) (multislot m))
(deftemplate b (slot z))
(watch activations)
(defrule ex (exists (a)) (a (z ?y)) =>)
(defrule ex-other (exists (b)) (a (z ?y)) =>)
(defrule ex-some (exists (a (z 1))) (a (z ?y)) =>)
(defrule ex-not (exists (a)) (not (b (z 5))) (a (z ?y)) =>)
(defrule no (not (b (z 7))) (a (z ?y)) =>)
(defrule t (test (> 2 1)) (a (z ?y)) =>)
(assert (a (m 2) (z 1)) (b (z 1)) (a (m) (z 1)) (a (z 2)))
(reset)
(assert (a (z 1)) (a (z 2)) (b (z 3)))
(retract 2)
(reset)
(assert (b (z 2)) (a (z 3)))
(exit)
