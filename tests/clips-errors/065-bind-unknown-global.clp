; expect: 2:27 expected global
(deffunction f (?x) (bind ?*nope* ?x))
(exit)
