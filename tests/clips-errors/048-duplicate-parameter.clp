; expect: 2:20 expected parameter
(deffunction f (?a ?a) ?a)
(exit)
