; A long agenda (an insertion walked past many activations of a higher salience)
; keeps its salience groups; then activations come and go at its head: one of a
; higher salience than the head's makes a new first group, the one activation of
; the first group fires and its group goes, a newer activation of the head's
; salience goes first in its group, a removed fact takes activations out of the
; middle of a group and the last one of a group.
(defrule lo (declare (salience -5)) (l ?x) => (printout t "l" ?x " "))
(defrule mid (m ?x) =>
  (printout t "m" ?x " ")
  (if (= (mod ?x 3) 0) then (assert (h ?x)))
  (if (and (< ?x 60) (= (mod ?x 4) 0)) then (assert (m (+ ?x 100)))))
(defrule hi (declare (salience 10)) (h ?x) => (printout t "h" ?x " ")
  (if (= (mod ?x 5) 0) then (assert (l (+ ?x 1000)))))
(defrule top (declare (salience 20)) (t ?x) => (printout t "t" ?x " "))
(reset)
(loop-for-count (?i 1 36) do (assert (m ?i)))
(loop-for-count (?i 1 34) do (assert (l ?i)))
(run 12)
(printout t crlf)
(assert (t 1))
(assert (h 500))
(run 3)
(printout t crlf)
(retract 20)
(retract 69)
(retract 37)
(assert (t 2) (l 99))
(run 20)
(printout t crlf)
(agenda)
(run)
(printout t crlf)
(agenda)
(exit)
