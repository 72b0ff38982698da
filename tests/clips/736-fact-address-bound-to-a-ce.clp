; a fact-address variable bound to a conditional element (`?x <- (or ...)`, `not`,
; `and`, `test`, `exists`) is CLIPS's defrule syntax error, the rule shown up to the
; token after the keyword
(defrule r1 ?x <- (or (a) (b)) => (retract ?x))
(defrule r2 (c) ?x <- (not (a)) => )
(defrule r3 ?x <- (and (a)) => )
(defrule r4 ?x <- (test (> 1 0)) => )
(defrule r5 (c) ?x <- (exists (a)) => )
(defrule ok ?x <- (a) => (retract ?x))
(rules)
(exit)
