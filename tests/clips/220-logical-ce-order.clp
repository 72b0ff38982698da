; Logical CEs come first in a rule and without gaps: CLIPS checks once the rule is
; read and shows it whole ([RULEPSR1] after another CE, [RULEPSR2] after a CE that
; follows logical ones, also in an `or` branch); an error met while reading comes first.
(defrule ok (logical (a)) (logical (b)) (c) => (assert (d)))
(defrule not-ok-1 (logical (a)) (b) (logical (c)) => (assert (d)))
(defrule not-ok-2 (a) (logical (b)) (logical (c)) => (assert (d)))
(defrule not-ok-3 (or (a) (logical (b))) (logical (c)) => (assert (d)))
(defrule not-ok-4 (a) (logical (b)) => (assert (d)) (+ 1))
(defrule not-ok-5 (a) (logical (b) (c)) (d ?x) => (printout t ?x crlf))
(defrule not-ok-6 (logical (a)) (b) (logical (c)) (e) (logical (f)) =>)
(list-defrules)
(reset)
(assert (a) (b) (c))
(run)
(facts)
(exit)
