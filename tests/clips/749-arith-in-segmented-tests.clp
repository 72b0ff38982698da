; Field constraints on elements of a segmented multislot that compare with `+`, `-`
; or `*` of another field and a constant (a board game's jump rule from round 19 of
; programs by others): integers, floats, mixed, a symbol where a number should be
; (the evaluator's error, which `sum-of-fields` also meets for every layout), `eq`
; and `neq` of a sum, and a sum of two fields.
(deftemplate world (multislot ball) (multislot men))
(defrule jump-left
  (world (ball ?x ?y) (men $?a - ?dx&:(= ?dx (- ?x 1)) ?dy&:(= ?dy (+ ?y 1)) - $?b))
  =>
  (printout t "jump-left " ?dx " " ?dy " after " (length$ ?a) crlf))
(defrule jump-scaled
  (world (ball ?x ?y) (men $? - ?dx&:(= ?dx (* ?x 2)) ?dy&:(eq ?dy (+ ?y 0.5)) - $?))
  =>
  (printout t "jump-scaled " ?dx " " ?dy crlf))
(defrule not-next
  (world (ball ?x ?) (men $? - ?dx&:(neq ?dx (- ?x 1)) ?dy&:(> ?dy (+ ?dx ?x)) - $?))
  =>
  (printout t "not-next " ?dx " " ?dy crlf))
(defrule sum-of-fields
  (world (ball ?x ?y) (men $? ?p&:(= ?p (+ ?x ?y)) $?))
  =>
  (printout t "sum-of-fields " ?p crlf))
(watch rules)
(assert (world (ball 3 4) (men - 2 5 - 6 8.5 - 2.0 5 - 9 20 - 7)))
(run)
(assert (world (ball 3.5 1) (men - 2.5 2 - 7.0 1.5 - 1 9 - 4.5)))
(run)
(exit)
