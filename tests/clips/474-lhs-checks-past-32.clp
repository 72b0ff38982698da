;; More than 32 test CEs in one rule: the static type check of a test CE after
;; the 32nd still runs ([RULECSTR2] in CE #35), and a rule of 41 harmless tests loads.
(deftemplate a (slot v (type STRING)))
(defrule r (a (v ?x)) (test (neq ?x 0)) (test (neq ?x 1)) (test (neq ?x 2)) (test (neq ?x 3)) (test (neq ?x 4)) (test (neq ?x 5)) (test (neq ?x 6)) (test (neq ?x 7)) (test (neq ?x 8)) (test (neq ?x 9)) (test (neq ?x 10)) (test (neq ?x 11)) (test (neq ?x 12)) (test (neq ?x 13)) (test (neq ?x 14)) (test (neq ?x 15)) (test (neq ?x 16)) (test (neq ?x 17)) (test (neq ?x 18)) (test (neq ?x 19)) (test (neq ?x 20)) (test (neq ?x 21)) (test (neq ?x 22)) (test (neq ?x 23)) (test (neq ?x 24)) (test (neq ?x 25)) (test (neq ?x 26)) (test (neq ?x 27)) (test (neq ?x 28)) (test (neq ?x 29)) (test (neq ?x 30)) (test (neq ?x 31)) (test (neq ?x 32)) (test (+ ?x 1)) =>)
(defrule ok (a (v ?x)) (test (neq ?x 0)) (test (neq ?x 1)) (test (neq ?x 2)) (test (neq ?x 3)) (test (neq ?x 4)) (test (neq ?x 5)) (test (neq ?x 6)) (test (neq ?x 7)) (test (neq ?x 8)) (test (neq ?x 9)) (test (neq ?x 10)) (test (neq ?x 11)) (test (neq ?x 12)) (test (neq ?x 13)) (test (neq ?x 14)) (test (neq ?x 15)) (test (neq ?x 16)) (test (neq ?x 17)) (test (neq ?x 18)) (test (neq ?x 19)) (test (neq ?x 20)) (test (neq ?x 21)) (test (neq ?x 22)) (test (neq ?x 23)) (test (neq ?x 24)) (test (neq ?x 25)) (test (neq ?x 26)) (test (neq ?x 27)) (test (neq ?x 28)) (test (neq ?x 29)) (test (neq ?x 30)) (test (neq ?x 31)) (test (neq ?x 32)) (test (neq ?x 33)) (test (neq ?x 34)) (test (neq ?x 35)) (test (neq ?x 36)) (test (neq ?x 37)) (test (neq ?x 38)) (test (neq ?x 39)) (test (str-length ?x)) => (printout t "ok " ?x crlf))
(rules)
(assert (a (v "abc")))
(run)
(exit)
