; expect: 2:31 expected integer
(defrule r (declare (salience high)) (a) => )
(exit)
