; A call with no value (printout, a deffunction ending in one) as a single-field
; slot's value stores nil, in assert, modify, duplicate and deffacts; in a multislot
; or an ordered fact it adds no field.
(deftemplate item (slot id) (multislot m) (slot n (default 3)))
(deffunction quiet () (printout t "quiet" crlf))
(assert (item (id (printout t "x" crlf))))
(assert (item (m a (printout t "y" crlf) b) (n (quiet))))
(assert (foo (printout t "z" crlf) bar))
(facts)
(defrule change
  ?f <- (item (id nil) (n 5))
  =>
  (duplicate ?f (id (printout t "d" crlf)) (n 4))
  (modify ?f (n (quiet)) (m (quiet))))
(deffacts start (item (id (quiet)) (n 5)))
(reset)
(facts)
(watch facts)
(run)
(facts)
(exit)
