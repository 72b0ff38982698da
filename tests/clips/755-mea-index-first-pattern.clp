; mea over a long agenda whose rules start with not, exists and test CEs (no first
; fact: last), rules of equal recency lists but other complexity, modify of facts
; in the middle of the agenda, and refresh
(deftemplate cell (slot id) (slot v))
(defrule mk ?g <- (go ?n) =>
  (retract ?g)
  (loop-for-count (?i 1 ?n) (assert (cell (id ?i) (v (mod ?i 4))))))
(defrule n1 (not (stop)) (cell (id ?i) (v ?v)) => (printout t "n1 " ?i crlf))
(defrule x1 (exists (cell (v 3))) (cell (id ?i) (v 1)) => (printout t "x1 " ?i crlf))
(defrule t1 (test (> 3 2)) (cell (id ?i) (v 2)) => (printout t "t1 " ?i crlf))
(defrule p1 (cell (id ?i) (v ?v)) (cell (id ?j&:(= ?j (+ ?i 1))) (v ?v2)) => (printout t "p1 " ?i crlf))
(defrule p2 (cell (id ?i) (v ?v&:(> ?v 0))) (cell (id ?j&:(= ?j (+ ?i 1))) (v ?v2)) => (printout t "p2 " ?i crlf))
(defrule m1 (declare (salience 5)) ?f <- (cell (id ?i&:(= (mod ?i 7) 0)) (v ?v&~9)) =>
  (modify ?f (v 9)) (printout t "m1 " ?i crlf))
(set-strategy mea)
(reset)
(assert (go 60))
(run 70)
(assert (stop))
(run 30)
(do-for-fact ((?s stop)) TRUE (retract ?s))
(run 20)
(refresh n1)
(set-strategy lex)
(run 30)
(set-strategy mea)
(run)
(exit)
