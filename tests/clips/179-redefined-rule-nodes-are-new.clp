; A redefined rule's pattern nodes that only the old rule used are made anew, as the
; newest (CLIPS removes the old rule first): they are tested before older nodes of the
; template, which decides what a halt after a pattern-network error still sees.
(deftemplate it (slot id) (slot w))
(deftemplate mk (slot id))
(defrule r3 (it (id ?j&:(any-factp ((?m mk)) (= ?m:id ?j)))) => )
(assert (mk (id 3)))
(defrule r3 (it (w ?w&:(> ?w 1))) (it (id ?j&:(any-factp ((?m mk)) (= ?m:id ?j)))) => )
(watch activations)
(assert (it (id 3) (w q)))
(assert (it (id 9) (w 5)))
(agenda)
(exit)
