(watch facts)
(watch rules)
(watch activations)
(deftemplate edge (slot from) (slot to))
(defrule path2
   (edge (from ?a) (to ?b))
   (edge (from ?b) (to ?c))
   =>
   (printout t "path " ?a " " ?b " " ?c crlf))
(defrule loop2
   (edge (from ?a) (to ?b))
   (edge (from ?b) (to ?a))
   =>
   (printout t "loop " ?a " " ?b crlf))
(reset)
(assert (edge (from a) (to b)))
(assert (edge (from b) (to c)))
(assert (edge (from c) (to a)))
(assert (edge (from b) (to a)))
(run)
(exit)
