; expect: 2:41 expected 'then'
(defrule r (a ?x) => (switch ?x (case 1 (printout t x))))
(exit)
