; pattern variables of ordered facts (and of a template whose first slot is a
; multislot) read by tests: fields before and after multifields, in join tests,
; predicate constraints, test CEs and right-hand sides
(deftemplate m (multislot items) (slot tag))
(deffacts start
  (w 1 "kalo" kalo)
  (w 2 "kami" kami)
  (w 3 "kalosu" kalosu)
  (v a b c d e)
  (v x)
  (v)
  (m (items p q r) (tag one))
  (m (items) (tag two))
  (m (items q) (tag three)))
(defrule pair
  (w ?i ?s ?)
  (w ?j&~?i ?t&:(eq (sub-string 1 2 ?s) (sub-string 1 2 ?t)) ?y)
  =>
  (printout t "pair " ?i " " ?j " " ?y crlf))
(defrule third
  (w ?i ? ?y&:(> (str-length ?y) 4))
  (test (> ?i 1))
  =>
  (printout t "third " ?i " " ?y crlf))
(defrule after-multi
  (v $?a ?last)
  (test (>= (length$ ?a) 0))
  =>
  (printout t "after " ?last " before " ?a crlf))
(defrule mid
  (v ?f $?mid ?l&:(neq ?f ?l))
  =>
  (printout t "mid " ?f " " ?mid " " ?l crlf))
(defrule second
  (v ? ?b&:(symbolp ?b) $?)
  =>
  (printout t "second " ?b crlf))
(defrule tmpl
  (m (items ?x $?rest) (tag ?g&:(symbolp ?g)))
  (test (neq ?x z))
  =>
  (printout t "tmpl " ?x " " ?rest " " ?g crlf))
(defrule tmpl-join
  (m (items $? ?x $?) (tag ?g))
  (m (items ?y&:(eq ?y ?x) $?) (tag ?h&~?g))
  =>
  (printout t "tmpl-join " ?x " " ?g " " ?h crlf))
(reset)
(run)
(exit)
