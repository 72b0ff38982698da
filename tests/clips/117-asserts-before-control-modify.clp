; Several asserts, a printout, a counter's modify and a control fact's modify in one
; right-hand side (a breadth-first search): the asserts' propagations wait with the
; counter's for the control fact's retract (rete::defer, Queued), so `pairs` never
; joins tags under the control fact only to lose them. Without (watch facts) or
; (watch activations); the printouts, the firing order, fact numbers, the agenda
; after a partial run and the facts must be CLIPS's. A repeated assert of a waiting
; fact makes none.
(watch rules)
(deftemplate ctx (slot s) (slot round (default 0)))
(deftemplate cnt (slot c))
(deftemplate edge (slot from) (slot to))
(deftemplate reached (slot node) (slot depth) (slot via))
(deftemplate done (slot node))
(deftemplate tag (slot node) (slot k))
(deffacts g (ctx (s expand)) (cnt (c 0)) (reached (node a) (depth 0) (via none))
   (edge (from a) (to b)) (edge (from a) (to c)) (edge (from b) (to d))
   (edge (from c) (to d)) (edge (from d) (to e)) (edge (from e) (to a))
   (edge (from c) (to f)) (edge (from f) (to g)) (edge (from g) (to b)))
(defrule expand
   ?x <- (ctx (s expand) (round ?r))
   (reached (node ?n) (depth ?d))
   (edge (from ?n) (to ?m))
   (not (reached (node ?m)))
   (not (done (node ?m)))
   ?k <- (cnt (c ?c))
   =>
   (assert (reached (node ?m) (depth (+ ?d 1)) (via ?n)))
   (printout t "reach " ?m " from " ?n crlf)
   (assert (tag (node ?m) (k ?c)))
   (assert (done (node ?m)))
   (assert (done (node ?m)))
   (modify ?k (c (+ ?c 1)))
   (printout t "count " ?c crlf)
   (modify ?x (s settle) (round (+ ?r 1))))
(defrule settle
   ?x <- (ctx (s settle))
   =>
   (modify ?x (s expand)))
(defrule pairs
   (declare (salience 5))
   (ctx (s expand))
   (tag (node ?a) (k ?i))
   (tag (node ?b&~?a) (k ?j))
   =>)
(defrule report
   (declare (salience -10))
   (reached (node ?n) (depth ?d) (via ?v))
   =>
   (printout t ?n " at " ?d " via " ?v crlf))
(reset)
(run 30)
(agenda)
(run)
(facts)
(agenda)
(exit)
