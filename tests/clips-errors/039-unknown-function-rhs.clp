; expect: 4:23 expected function
; keeps: 42
(deffunction twice (?x) (* 2 ?x))
(defrule r (a ?x) => (frobnicate ?x))
(twice 21)
(exit)
