; A test in the pattern or join network fails with an error: CLIPS reports it (naming
; the slot, or the field of an ordered fact, and the pattern and rule), takes the test
; as false, keeps the fact, and halts: a rule's or deffunction's remaining actions and
; a progn's do not run. A bare assert at the prompt still shows its fact.
(watch rules)
(deftemplate cnt (slot a) (slot c) (multislot m))
(defrule p (cnt (a ?a) (c ?c&:(> ?c 1))) =>)
(defrule p2 (cnt (m ?x ?y&:(> ?y 1))) =>)
(defrule q (data ?x ?y&:(> ?y 1)) =>)
(defrule q2 (data $? ?y&:(> ?y 2)) =>)
(defrule j (cnt (a ?a)) (data ?d ?e) (test (> ?d ?a)) =>)
(defrule nj (cnt (a ?a)) (not (data ?d&:(< ?d ?a) ?)) => (printout t "nothing below " ?a crlf))
(defrule go (initial-fact) =>
  (assert (cnt (a 1) (c x)))
  (printout t "not printed" crlf)
  (assert (cnt (a 2) (c 5))))
(reset)
(run)
(facts)
(assert (cnt (a 1) (c 5) (m 1 x)))
(progn (assert (data a b)) (printout t "not printed" crlf))
(deffunction f () (assert (data c d)) (printout t "not printed" crlf) 7)
(f)
(assert (data 0 3) (data 5 1))
(run)
(facts)
(exit)
