; expect: 3:14 expected not a builtin
; keeps: 2
(deffunction max (?a ?b) ?a)
(max 1 2)
(exit)
