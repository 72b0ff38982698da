; expect: 2:21 expected '('
(deffunction double ?x (* 2 ?x))
(exit)
