; expect: 2:30 expected expression
(defrule r (declare (salience)) (a) => )
(exit)
