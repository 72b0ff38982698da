; expect: 3:34 expected fact-address
(deftemplate t (slot a))
(defrule r (t (a ?x)) => (modify 1 (a 2)))
(exit)
