; Facts of changing sizes come and go while rules fire: a new fact takes the value
; cells a retracted one left when they are enough, else cells at the arena top, and
; compaction (when the top reaches the arena's end) packs the facts by position.
; Tens of thousands of cells pass through an arena that holds far fewer at a time;
; every fact must keep its values.
(deftemplate item (slot id) (multislot data))
(deftemplate ctr (slot n) (multislot hist))
(defglobal ?*sum* = 0 ?*n* = 0)
(deffunction cells (?n)
   (subseq$ (create$ a b c d e f g h i j k) 1 ?n))
(defrule churn
   ?f <- (item (id ?i&:(< ?i 24000)) (data $?d))
   =>
   (retract ?f)
   (assert (item (id (+ ?i 200)) (data (cells (mod (* ?i 7) 12)) ?i))))
(defrule grow
   (declare (salience 5))
   ?c <- (ctr (n ?n&:(< ?n 3000)) (hist $?h))
   (item (id ?i&:(= (mod ?i 8) (mod ?n 8))))
   =>
   (bind ?h2 (create$ $?h ?n))
   (if (> (length$ ?h2) 9) then (bind ?h2 (rest$ (rest$ (rest$ (rest$ ?h2))))))
   (modify ?c (n (+ ?n 1)) (hist ?h2)))
(defrule check
   (declare (salience -10))
   (item (id ?i) (data $?d))
   =>
   (bind ?*n* (+ ?*n* 1))
   (bind ?*sum* (+ ?*sum* ?i (* 3 (length$ ?d)))))
(deffacts start (ctr (n 0) (hist)))
(reset)
(loop-for-count (?i 0 199) do (assert (item (id ?i) (data (cells (mod ?i 12))))))
(run)
(printout t "checked " ?*n* " sum " ?*sum* crlf)
(facts 0 5)
(facts)
(exit)
