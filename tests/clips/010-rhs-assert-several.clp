(watch facts)
(watch rules)
(watch activations)
(defrule expand
   (seed ?x)
   =>
   (assert (child ?x 1) (child ?x 2) (child ?x 1)))
(defrule count-child
   (child ?x ?n)
   =>
   (printout t "child " ?x " " ?n crlf))
(reset)
(assert (seed a))
(run)
(facts)
(exit)
