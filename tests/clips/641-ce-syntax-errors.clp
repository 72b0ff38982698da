; Syntax errors in rule conditions as CLIPS 6.30 reports them, each with the
; rule shown after ERROR: up to where CLIPS stopped: a constraint ending in a
; dangling &, | or ~; (test) with no expression ("function calls") or two
; ("test conditional element"); binding patterns (?x <- ?y, a lone ?x, ?x <-
; not followed by a pattern); (not A B) read whole; (bind) with no variable or
; a constant, in rules, deffunctions and at the prompt. Nothing is kept.
(defrule good (a ?x) (test (> ?x 1)) => (printout t "good " ?x crlf))
(defrule r4 (x ?a&) =>)
(defrule r5 (x ?a&~) =>)
(defrule r6 (x ~) =>)
(defrule r7 (x a|) =>)
(defrule r8 (x a | ) =>)
(defrule r2 (test) =>)
(defrule r3 (test (> 1 2) (< 1 2)) =>)
(defrule r3b (a ?x) (test (> ?x 2) 7) =>)
(defrule r11 ?x <- ?y <- (a) =>)
(defrule r12 ?x <- ?y =>)
(defrule r13 (a) ?x =>)
(defrule r13b (a) ?x <- 5 =>)
(defrule r14 (not (a) (b)) =>)
(defrule r14b (a ?x) (not (b ?x) (c) (d)) =>)
(defrule r15 (a) => (bind))
(defrule r15b (a) => (bind "x" 1))
(deffunction f1 () (bind))
(deffunction f2 () (bind 3 4))
(bind)
(bind 3)
(list-defrules)
(list-deffunctions)
(assert (a 5))
(run)
(exit)
