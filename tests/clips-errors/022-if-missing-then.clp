; expect: 2:34 expected 'then'
(deffunction f (?x) (if (> ?x 0) 1 else 2))
(exit)
