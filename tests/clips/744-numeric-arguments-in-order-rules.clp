; The numeric functions take their arguments one at a time in rules and deffunctions
; too (see 743): a pattern's field constraint (`?p&:(= ?p (+ ?x ?y))` on a segmented
; multislot, the board game's rule of round 19), a slot predicate, a `test` CE (reported
; with the join's context), a rule's actions and a deffunction's, with a deffunction
; that prints as the argument after a bad one. A bad divisor of `/` in an action also
; divides by zero.
(deffunction side (?tag) (printout t "side " ?tag crlf) 1)
(deffunction f1 (?x) (+ ?x (side f1)))
(deffunction f2 (?x) (printout t "f2 " (= ?x (side f2)) crlf) (printout t "f2 after" crlf))
(deffunction f3 (?x ?y) (/ 10 ?x (side f3) ?y))
(deftemplate world (multislot ball) (multislot men))
(deftemplate v (slot x) (slot y))
(defrule sum-of-fields
  (world (ball ?x ?y) (men $? ?p&:(= ?p (+ ?x ?y)) $?))
  =>
  (printout t "sum-of-fields " ?p crlf))
(defrule test-ce
  (v (x ?x) (y ?y))
  (test (< ?x (side test-ce) ?y))
  =>
  (printout t "test-ce " ?x " " ?y crlf))
(defrule slot-pred
  (v (x ?x&:(>= ?x (side slot-pred))))
  =>
  (printout t "slot-pred " ?x crlf))
(defrule join-pred
  (v (x ?x))
  (world (ball ?b ?)
         (men ?m&:(<> ?x ?m (side join-pred)) $?))
  =>
  (printout t "join-pred " ?x " " ?b crlf))
(defrule rhs
  (v (x ?x) (y ?y))
  =>
  (printout t "rhs " (* ?x (side rhs)) crlf)
  (printout t "rhs after " (div 6 ?y (side rhs-div)) crlf))
(defrule rhs-slash
  (v (x ?x) (y ?y))
  =>
  (/ 10 ?x (side rhs-slash) ?y)
  (printout t "rhs-slash after" crlf))
(watch rules)
(assert (world (ball a 1) (men - 2 2 -)))
(run)
(assert (world (ball 3 1) (men 2 2 -)))
(run)
(assert (v (x q) (y 2)))
(run)
(assert (v (x 3) (y 0)))
(run)
(assert (v (x 3.0) (y 0.5)))
(run)
(f1 b)
(f1 2)
(f2 c)
(f2 1)
(f3 0 2)
(f3 2 0)
(f3 z 1)
(f3 1 z)
(exit)
