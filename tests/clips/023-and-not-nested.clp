(watch facts)
(watch rules)
(watch activations)
(defrule no-complete-pair
   (item ?x)
   (not (and (part ?x a) (part ?x b)))
   =>
   (printout t "incomplete " ?x crlf))
(defrule all-have-parts
   (not (and (item ?x) (not (part ?x ?))))
   =>
   (printout t "every item has a part" crlf))
(reset)
(assert (item 1) (item 2))
(assert (part 1 a))
(agenda)
(assert (part 1 b))
(agenda)
(assert (part 2 a))
(agenda)
(run)
(exit)
