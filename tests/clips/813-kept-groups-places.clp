; A long agenda (over 32 activations, so its salience groups are kept) where
; activations of other saliences come and go one by one: each makes and empties a
; group of its own; depth puts new ones first in their group, breadth last, and a
; re-sort (refresh-agenda, set-strategy) inserts them again in their old order
(defglobal ?*n* = 0)
(deftemplate job (slot id) (slot kind))
(defrule base ?j <- (job (id ?i) (kind base)) => (retract ?j) (printout t "b" ?i " "))
(defrule hi (declare (salience 5)) ?j <- (job (id ?i) (kind hi)) =>
  (retract ?j) (printout t "h" ?i " "))
(defrule lo (declare (salience -5)) ?j <- (job (id ?i) (kind lo)) =>
  (retract ?j) (printout t "l" ?i " "))
(defrule chain (declare (salience -3)) ?c <- (chain ?k&:(< ?k 6)) =>
  (retract ?c) (printout t "c" ?k " ")
  (assert (chain (+ ?k 1)))
  (assert (job (id (+ 200 ?k)) (kind hi)))
  (assert (job (id (+ 300 ?k)) (kind lo))))
(defrule mid (declare (salience 2)) (job (id ?i&:(= (mod ?i 7) 0)) (kind base)) =>
  (printout t "m" ?i " "))
(deffunction jobs (?from ?to ?kind)
  (loop-for-count (?i ?from ?to) do (assert (job (id ?i) (kind ?kind)))))
(reset)
(jobs 1 40 base)
(assert (chain 0))
(jobs 41 43 hi)
(jobs 44 46 lo)
(agenda)
(run 12)
(printout t crlf)
(set-strategy breadth)
(jobs 47 52 base)
(jobs 53 55 hi)
(run 15)
(printout t crlf)
(refresh-agenda)
(set-strategy depth)
(jobs 56 60 lo)
(run 10)
(printout t crlf)
(agenda)
(run)
(printout t crlf)
(exit)
