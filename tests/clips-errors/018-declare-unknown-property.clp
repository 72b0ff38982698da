; expect: 2:22 expected salience
(defrule r (declare (priority 5)) (a) => )
(exit)
