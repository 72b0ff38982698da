(watch facts)
(watch rules)
(deftemplate cell (slot x) (slot v (default 0)))
(reset)
(bind ?f (assert (cell (x 1))))
?f
(printout t "asserted " ?f crlf)
(modify ?f (v 5))
(bind ?g (assert (cell (x 2))))
(retract ?g)
(retract ?g)
(defrule show
   ?c <- (cell (x ?x) (v ?v))
   =>
   (printout t "cell " ?x " = " ?v " is " ?c crlf)
   (bind ?new (assert (seen ?x)))
   (printout t "new fact " ?new crlf))
(run)
(exit)
