; Side effects of tests while a rule is defined: where CLIPS runs the test decides.
; A join fed by an older join or pattern is primed outside CLIPS's join operations
; (assert, bind and printout work there); a test reached by driving the existing
; facts through a pattern new to the rule runs inside them (FACTMNGR1/2). `(blk ?)`
; is a pattern of its own, `(blk ?y)` shares `oldnot`'s
(defglobal ?*n* = 0)
(watch facts)
(watch rules)
(watch activations)
(deffacts d (a 1) (a 2) (blk 1))
(defrule old (a ?x) => (printout t "old " ?x crlf))
(defrule oldnot (a ?x) (not (blk ?x)) => (printout t "oldnot " ?x crlf))
(reset)
(defrule newA (a ?x) (blk ?) (test (progn (printout t "TA " ?x crlf) (assert (c A ?x)))) => )
(defrule newB (a ?x) (blk ?y) (test (progn (printout t "TB " ?x crlf) (assert (c B ?x)))) => )
(defrule newC (blk ?y) (a ?x) (test (progn (printout t "TC " ?x crlf) (assert (c C ?x)))) => )
(defrule newD (a ?x) (test (> ?x 0)) (blk ?y) (test (progn (printout t "TD " ?x crlf) (assert (c D ?x)))) => )
(defrule newE (a ?x) (test (progn (printout t "TE " ?x crlf) (assert (c E ?x)))) (blk ?y) => )
(defrule n1 (a ?x) (test (progn (bind ?*n* (+ ?*n* 1)) (printout t "n1 " ?x " " ?*n* crlf) TRUE)) =>)
(defrule n3 (a ?x) (test (assert-string (str-cat "(s " ?x ")"))) (s ?x) =>)
(defrule n4 (a ?x) (test (assert (m ?x) (m x ?x))) (m ?y) =>)
(defrule n5 (a ?x) (test (assert (a ?x))) =>)
(facts)
(agenda)
(assert (a 3))
(agenda)
(run)
(exit)
