; A right-hand side of many asserts (an init rule), and asserts and printouts before
; a modify: more facts than may wait for the modify (rete::defer's queue), so the
; first ones are built at once. Results and order as in CLIPS.
(deftemplate ctl (slot n) (slot state))
(defrule init
  =>
  (assert (item 1)) (assert (item 2)) (assert (item 3)) (assert (item 4))
  (assert (item 5)) (assert (item 6)) (assert (item 7)) (assert (item 8))
  (assert (item 9)) (assert (item 10)) (assert (item 11)) (assert (item 12))
  (assert (ctl (n 0) (state go))))
(defrule step
  ?c <- (ctl (n ?n&:(< ?n 3)) (state go))
  =>
  (assert (a ?n)) (printout t "a " ?n crlf)
  (assert (b ?n)) (assert (c ?n)) (printout t "c " ?n crlf)
  (assert (d ?n)) (assert (e ?n)) (assert (f ?n))
  (printout t "before modify " ?n crlf)
  (modify ?c (n (+ ?n 1))))
(defrule seen (item ?i) (ctl (n ?n)) (test (= ?i (* 4 ?n))) => (printout t "item " ?i " at " ?n crlf))
(defrule pair (a ?n) (f ?n) (ctl (n ?m&:(> ?m ?n))) => (printout t "pair " ?n " " ?m crlf))
(reset)
(run)
(agenda)
(facts)
(exit)
