; A single-field slot given two values or none, as CLIPS 6.30 reports it:
; [TMPLTDEF2] in deffacts, RHS asserts and deffunctions (the second value's
; first token glued to the first after ERROR:), a pattern with a second field
; ("deftemplate patterns"), a multifield variable ([TMPLTDEF2], the slot read
; whole) or no field; and [PRNTUTIL6] for a variable in deffacts (the
; deffacts shown whole). Nothing of them is kept.
(deftemplate t (slot a) (multislot m))
(deffacts good (t (a 1) (m 1 2)))
(deffacts d1 (t (a 12 (+ 1 2))))
(deffacts d2 (t (a "x" y)))
(deffacts d3 (t (a)))
(deffacts d4 (x ?y) (z 1))
(deffacts d5 "comment" (z 1) (t (a ?y)))
(defrule r1 => (assert (t (a 1 2))))
(deffunction f1 () (assert (t (a 1 2))))
(defrule r2 (t (a ?x $?y)) =>)
(defrule r2b (t (a 1 2)) =>)
(defrule r3 (t (a $?y)) =>)
(defrule r4 (t (a)) =>)
(assert (t (a 1 2)))
(assert (t (a)))
(list-deffacts)
(list-defrules)
(list-deffunctions)
(reset)
(facts)
(exit)
