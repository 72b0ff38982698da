; Multifield LHS variables read where they lie in the fact (host speed-ups):
; equality of two of them in a join (`$?rest` in two patterns, a field after a
; multifield in both), the hash keys of such joins, `length$` of one in a
; comparison, `member$` and its `not` in joins, against the evaluator's answers
; (empty segments, a float that is not the integer, strings, `$?x` and `?x`
; forms, a `length$` of a single field).
(deftemplate stack (multislot items) (slot tag))
(deftemplate want (multislot items))
(defrule same-tail
  (goal $?g ?top $?rest)
  (stack (items ?top $?rest))
  =>
  (printout t "same-tail " ?top " / " (length$ ?rest) " " ?g crlf))
(defrule same-after-multi
  (goal $? ?x $?)
  (pile $? ?x $?)
  =>
  (printout t "same-after-multi " ?x crlf))
(defrule blocked-tail
  (goal ?a $?rest)
  (not (stack (items $? ?a $?rest)))
  =>
  (printout t "blocked-tail " ?a " " (length$ $?rest) crlf))
(defrule len-test
  (stack (items $?i&:(> (length$ $?i) 2)) (tag ?t))
  =>
  (printout t "len-test " ?t " " (length$ ?i) crlf))
(defrule len-join
  (want (items $?w))
  (stack (items $?i&:(>= (length$ ?i) (length$ $?w))) (tag ?t))
  =>
  (printout t "len-join " ?t " " (length$ $?w) crlf))
(defrule member-join
  (goal $? ?x $?)
  (stack (items $?i&:(member$ ?x ?i)) (tag ?t))
  =>
  (printout t "member-join " ?x " in " ?t " at " (member$ ?x $?i) crlf))
(defrule not-member-join
  (want (items ?w $?))
  (goal ?x $?)
  (stack (items $?i&:(not (member$ ?x $?i))) (tag ?t&~s5))
  =>
  (printout t "not-member-join " ?w " " ?x " " ?t crlf))
(defrule member-not
  (want (items $?w))
  (stack (items $?i&:(not (member$ "s" $?i))) (tag ?t))
  =>
  (printout t "member-not " ?t crlf))
(defrule member-sym
  (stack (items $?i&:(member$ b $?i)) (tag ?t))
  =>
  (printout t "member-sym " ?t " " (member$ b ?i) crlf))
(defrule length-single
  (stack (tag ?t&:(= (length$ ?t) 2)))
  =>
  (printout t "length-single " ?t crlf))
(watch rules)
(assert (goal a b c))
(assert (stack (items b c) (tag s1)))
(assert (stack (items a b c) (tag s2)))
(assert (stack (items c) (tag s3)))
(assert (stack (items) (tag s4)))
(assert (stack (items 1 1.0 "s" b) (tag s5)))
(assert (pile x 1.0 c))
(assert (want (items p q)))
(run)
(assert (goal 1 x))
(assert (goal 1.0))
(assert (stack (items "s") (tag xy)))
(run)
(exit)
