; expect: 2:12 expected global
(defglobal ?x = 5)
(exit)
