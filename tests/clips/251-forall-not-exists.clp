(watch facts)
(watch rules)
(watch activations)
(defrule every-a-has-b (declare (salience 10))
   (forall (a ?x) (b ?x))
   =>
   (printout t "every a has a b" crlf))
(defrule some-a-lacks-b
   (not (forall (a ?x) (b ?x)))
   =>
   (printout t "some a lacks a b" crlf))
(defrule exists-forall (declare (salience -5))
   (exists (forall (a ?x) (b ?x&~none)))
   =>
   (printout t "exists over forall" crlf))
(defrule big-a-have-no-c
   (forall (a ?x&:(> ?x 1)) (not (c ?x)))
   =>
   (printout t "no big a has a c" crlf))
(defrule each-a-has-some-d
   (forall (a ?x) (exists (d ?x ?)))
   =>
   (printout t "each a has some d" crlf))
(defrule per-group (declare (salience 5))
   (group ?g)
   (forall (member ?g ?m) (ok ?m) (test (neq ?m bad)))
   =>
   (printout t "group " ?g " all ok" crlf))
(defrule pairs
   (forall (and (a ?x) (b ?x)) (c ?x) (d ?x ?))
   =>
   (printout t "every a-b pair has c and d" crlf))
(defrule only-tests
   (e ?y)
   (forall (a ?x) (test (< ?x ?y)))
   =>
   (printout t "every a is below " ?y crlf))
(reset)
(run)
(assert (a 1))
(run)
(assert (b 1) (e 5))
(run)
(assert (a 2) (c 2) (group g1) (member g1 m1))
(run)
(assert (b 2) (d 1 x) (ok m1))
(run)
(retract 7)
(assert (d 2 y) (c 1))
(run)
(assert (member g1 bad) (ok bad) (e 2))
(run)
(matches every-a-has-b)
(matches some-a-lacks-b)
(matches big-a-have-no-c)
(matches only-tests)
(agenda)
(exit)
