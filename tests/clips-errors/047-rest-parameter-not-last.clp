; expect: 5:24 expected last
; keeps: 15
; keeps: [EXPRNPSR3] Missing function declaration for f.
(deffunction ok (?x) (* ?x 3))
(deffunction f ($?rest ?x) (length$ ?rest))
(ok 5)
(f 1 2)
(exit)
