; expect: 2:17 expected '='
(defglobal ?*x* 5)
(exit)
