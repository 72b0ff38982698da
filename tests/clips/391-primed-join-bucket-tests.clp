; A join primed while facts exist, whose left memory is hashed on ?k: a fact entering
; its right side meets only the partial matches of its bucket, so a test that would
; fail with an error on the other partial matches (> of a symbol) never runs on them.
(deftemplate a (slot k) (slot v))
(deftemplate b (slot k) (slot v))
(watch activations)
(defrule r1 (a (k ?k) (v ?v)) (b (k ?k)) => )
(assert (a (k 1) (v x)) (a (k 2) (v 5)) (a (k 3) (v 7)))
(defrule r2 (a (k ?k) (v ?v)) (b (v ?w&:(> ?v 1)) (k ?k)) => )
(assert (b (k 2) (v 0)))
(assert (b (k 3) (v 0)))
(assert (b (k 1) (v 0)))
(exit)
