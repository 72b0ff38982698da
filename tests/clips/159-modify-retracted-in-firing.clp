; A rule's actions modify (or duplicate) a fact they already retracted or modified:
; CLIPS still has its values and asserts the modified copy, retracting nothing
(watch facts)
(watch rules)
(deftemplate ctx (slot s) (slot n (default 0)))
(defrule twice ?x <- (ctx (s a)) => (modify ?x (s b)) (modify ?x (s c) (n 1)))
(defrule gone ?x <- (ctx (s c)) => (retract ?x) (modify ?x (s d)) (duplicate ?x (s z) (n 2)) (printout t ?x crlf))
(defrule rebind ?x <- (ctx (s d)) => (bind ?x (modify ?x (s e))) (modify ?x (n 5)))
(reset)
(assert (ctx (s a)))
(run)
(facts)
(exit)
