; A variable a constraint reads after `&` (or `~`) before any pattern binds it:
; [ANALYSIS4] naming the CE and its slot or field, the whole rule shown; nothing defined.
(watch facts)
(watch rules)
(deftemplate foo (field x) (field y))
(defrule r1 (foo (y ?x1&~?x2) (x ?x2)) =>)
(defrule r2 (a ?x&~?y) (b ?y) =>)
(defrule r4 (a ?x) (b ?x&?z) =>)
(defrule r5 (not (a ?x&~?q)) =>)
(defrule good (foo (x ?x2) (y ?x1&~?x2)) => (printout t ?x1 " " ?x2 crlf))
(list-defrules)
(assert (foo (x 3) (y 4)) (foo (x 4) (y 4)))
(run)
(exit)
