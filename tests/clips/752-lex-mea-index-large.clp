; lex and mea over agendas long enough for the host's ordered index (hundreds of
; activations): shared facts tie the most recent keys, retracts take activations out
; of the middle, strategy switches re-sort mid-run, three salience levels
(defglobal ?*n* = 0)
(defrule mk (declare (salience 50)) ?g <- (go ?n) =>
  (retract ?g)
  (loop-for-count (?i 1 ?n) (assert (item ?i (mod (* ?i 7) 5))))
  (assert (kind a) (kind b)))
(defrule pair (item ?i ?w) (item ?j&:(> ?j ?i) ?w) =>
  (bind ?*n* (+ ?*n* 1)) (printout t "pair " ?i " " ?j crlf))
(defrule pick (item ?i ?w) (kind ?k) =>
  (printout t "pick " ?i " " ?k crlf))
(defrule hi (declare (salience 10)) (item ?i 3) (kind b) =>
  (printout t "hi " ?i crlf))
(defrule lo (declare (salience -10)) (kind ?k) (item ?i 1) =>
  (printout t "lo " ?k " " ?i crlf))
(defrule drop (declare (salience 5)) ?f <- (item ?i 4) (kind a) (test (= (mod ?i 3) 0)) =>
  (retract ?f) (printout t "drop " ?i crlf))
(set-strategy lex)
(reset)
(assert (go 40))
(run 60)
(printout t "agenda " (length$ (get-focus-stack)) crlf)
(set-strategy mea)
(run 60)
(assert (kind c))
(run 40)
(set-strategy depth)
(run 20)
(set-strategy lex)
(assert (item 100 2) (item 101 2))
(run 80)
(set-strategy mea)
(assert (item 102 3))
(run)
(printout t "pairs " ?*n* crlf)
(set-strategy mea)
(reset)
(assert (go 30))
(run 1)
(assert (kind z))
(run 100)
(set-strategy lex)
(run)
(exit)
