(watch facts)
(watch rules)
(watch activations)
(defrule either
   (item ?x)
   (or (color ?x red) (size ?x big))
   =>
   (printout t "either " ?x crlf))
(defrule both-or
   (or (a) (b))
   (or (c) (d))
   =>
   (printout t "combo" crlf))
(reset)
(assert (item 1) (color 1 red) (size 1 big))
(assert (a) (b) (c) (d))
(agenda)
(run)
(exit)
