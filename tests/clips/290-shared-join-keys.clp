; Rules sharing a join prefix whose next patterns join on different variables
; (several keyed children of one join memory), right-activated while the shared
; memory is full: which partial matches each new fact meets, and in what order.
(deftemplate j (slot id) (slot a) (slot b) (slot c))
(deftemplate e (slot p) (slot q) (slot tag))
(deftemplate s (slot v))

(defrule on-a
  (s (v go))
  (j (id ?i) (a ?a) (b ?b) (c ?c))
  (e (p ?i) (q ?a) (tag x))
  =>
  (printout t "on-a " ?i " " ?a crlf))

(defrule on-b
  (s (v go))
  (j (id ?i) (a ?a) (b ?b) (c ?c))
  (e (p ?i) (q ?b) (tag y))
  =>
  (printout t "on-b " ?i " " ?b crlf))

(defrule on-c
  (s (v go))
  (j (id ?i) (a ?a) (b ?b) (c ?c))
  (e (p ?i) (q ?c))
  =>
  (printout t "on-c " ?i " " ?c crlf))

(defrule on-a-again
  (s (v go))
  (j (id ?i) (a ?a) (b ?b) (c ?c))
  (e (p ?i) (q ?a) (tag z))
  =>
  (printout t "on-a-again " ?i " " ?a crlf))

(defrule none-b
  (s (v go))
  (j (id ?i) (a ?a) (b ?b) (c ?c))
  (not (e (p ?i) (q ?b)))
  =>
  (printout t "none-b " ?i crlf))

(defrule some-c
  (s (v go))
  (j (id ?i) (a ?a) (b ?b) (c ?c))
  (exists (e (p ?c) (q ?i)))
  =>
  (printout t "some-c " ?i crlf))

(defrule by-ab
  (s (v go))
  (j (id ?i) (a ?a) (b ?b) (c ?c))
  (e (p ?a) (q ?b))
  =>
  (printout t "by-ab " ?i " " ?a " " ?b crlf))

(defrule by-list
  (s (v go))
  (j (id ?i) (a ?a) (b ?b) (c ?c))
  (e (p ?c) (q ?a) (tag ?t))
  =>
  (printout t "by-list " ?i " " ?t crlf))

(watch rules)
(reset)
(assert (s (v go)))
(assert (j (id 1) (a 10) (b 20) (c 30)))
(assert (j (id 2) (a 10) (b 21) (c 31)))
(assert (j (id 3) (a 11) (b 20) (c 30)))
(assert (j (id 4) (a 1.0) (b "x") (c x)))
(assert (j (id 5) (a 12) (b 20) (c 5)))
(run)
(assert (e (p 1) (q 10) (tag x)))
(assert (e (p 1) (q 20) (tag y)))
(assert (e (p 2) (q 31) (tag x)))
(assert (e (p 3) (q 11) (tag z)))
(assert (e (p 4) (q 1.0) (tag x)))
(assert (e (p 4) (q 1) (tag x)))
(assert (e (p 4) (q x) (tag y)))
(assert (e (p 4) (q "x") (tag y)))
(assert (e (p x) (q 4)))
(assert (e (p 10) (q 20) (tag w)))
(assert (e (p 30) (q 1) (tag w)))
(assert (e (p 30) (q 11) (tag v)))
(assert (e (p 5) (q 20)))
(run)
(assert (j (id 6) (a 10) (b 20) (c 30)))
(assert (e (p 6) (q 30) (tag y)))
(run)
(undefrule on-b)
(assert (e (p 1) (q 30) (tag q)))
(assert (e (p 2) (q 21) (tag y)))
(assert (e (p 3) (q 20) (tag y)))
(assert (e (p 10) (q 20) (tag w2)))
(assert (e (p 30) (q 10) (tag m)))
(assert (e (p 30) (q 11) (tag m)))
(run)
(do-for-all-facts ((?f j)) (= ?f:id 4) (retract ?f))
(assert (e (p 1) (q 20) (tag z)))
(assert (e (p 6) (q 10) (tag z)))
(assert (e (p 6) (q 10) (tag x)))
(run)
(do-for-all-facts ((?f j)) (= ?f:id 2) (modify ?f (a 11)))
(assert (e (p 2) (q 11) (tag z)))
(assert (e (p 11) (q 21)))
(run)
(defrule on-b2
  (s (v go))
  (j (id ?i) (a ?a) (b ?b) (c ?c))
  (e (p ?i) (q ?b) (tag y))
  =>
  (printout t "on-b2 " ?i " " ?b crlf))
(run)
(assert (e (p 5) (q 20) (tag y)))
(assert (e (p 6) (q 20) (tag y)))
(run)
(facts)
(exit)
