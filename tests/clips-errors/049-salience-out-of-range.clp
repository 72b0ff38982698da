; expect: 2:31 expected salience
(defrule r (declare (salience 20000)) (a) => )
(exit)
