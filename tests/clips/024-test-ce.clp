(watch facts)
(watch rules)
(watch activations)
(defrule bigger
   (num ?a)
   (num ?b)
   (test (> ?a ?b))
   =>
   (printout t ?a " > " ?b crlf))
(defrule even
   (num ?a)
   (test (= (mod ?a 2) 0))
   =>
   (printout t ?a " is even" crlf))
(reset)
(assert (num 1) (num 2) (num 3))
(run)
(exit)
