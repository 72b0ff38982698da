; A numeric call's later `(length$ ?l)` of an LHS multifield variable prints nothing and
; cannot fail, so it may be read eagerly; of a single-field variable it may print, and
; CLIPS leaves it unread after an argument that is no number.
(deftemplate m (slot j) (multislot lw) (slot k))
(defrule multi
  (declare (salience 3))
  (m (j ?j) (lw $?lw))
  =>
  (printout t "multi " ?j " " (+ ?j (length$ ?lw)) crlf)
  (printout t "mixed " (- ?j (length$ ?lw) 1) " " (* 2 ?j (length$ $?lw)) crlf)
  (printout t "cmp " (> ?j (length$ ?lw)) " " (= (length$ ?lw) ?j) crlf))
(defrule single
  (declare (salience 2))
  (m (j ?j) (k ?k))
  =>
  (printout t "single " (+ ?j (length$ ?k)) crlf))
(defrule bound
  (declare (salience 1))
  ?m <- (m (j ?j) (lw $?lw))
  =>
  (bind ?x (+ ?j (length$ ?lw)))
  (printout t "bound " ?x crlf)
  (modify ?m (k (- (length$ ?lw) ?j))))
(assert (m (j 1) (lw a b c) (k x)))
(run)
(facts)
(assert (m (j sym) (lw a b) (k 7)))
(run)
(run)
(run)
(assert (m (j 2.5) (lw) (k 3)))
(run)
(run)
(run)
(facts)
(exit)
