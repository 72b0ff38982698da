; After a test in the pattern network fails with an error, CLIPS evaluates no fact-set
; query for the rest of that fact's propagation (execution is halting): the fact does
; not match a later pattern whose test runs a query. We still run the query.
(watch activations)
(deftemplate it (slot id) (slot w))
(deftemplate mk (slot id))
(defrule q (it (id ?j&:(any-factp ((?m mk)) (= ?m:id ?j)))) =>)
(defrule p (it (w ?w&:(> ?w 1))) =>)
(assert (mk (id 3)))
(assert (it (id 3) (w q)))
(agenda)
(exit)
