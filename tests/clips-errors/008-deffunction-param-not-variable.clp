; expect: 2:22 expected parameter
(deffunction add (?a b) (+ ?a b))
(exit)
