; expect: 2:35 expected salience
(defrule r (declare (salience 1) (salience 2)) (a) => )
(exit)
