; expect: 4:23 expected deftemplate name
; keeps: ok 5
(defrule first (declare (salience 5)) (a ?x) => (printout t "ok " ?x crlf))
(defrule late (a ?x) (declare (salience 5)) => (printout t "late" crlf))
(assert (a 5))
(run)
(exit)
