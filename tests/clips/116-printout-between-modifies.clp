; A printout between a counter's modify and a control fact's modify (Miss Manners as
; published): the counter's propagation may wait for the control fact's retract while
; the printout's text is held (rete::defer). Without (watch facts) or (watch
; activations), which build every propagation at once; the printouts, the firing
; order, the facts and the agenda must be CLIPS's. The second printout's text (a
; 350-byte note) is more than is held: it builds the propagation first.
(watch rules)
(defglobal ?*out* = t)
(deftemplate cnt (slot c))
(deftemplate ctx (slot s))
(deftemplate item (slot id) (slot v) (slot note (default "")))
(deffacts d (cnt (c 0)) (ctx (s go))
   (item (id 1) (v a)) (item (id 2) (v b)) (item (id 3) (v a) (note "long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long long ")))
(defrule step
   ?x <- (ctx (s go))
   (item (id ?i) (v ?v) (note ?note))
   ?n <- (cnt (c ?c&:(< ?c 5)))
   =>
   (modify ?n (c (+ ?c 1)))
   (printout ?*out* "step " ?c " item " ?i crlf)
   (printout t ?v tab ?note crlf)
   (modify ?x (s back)))
(defrule back
   ?x <- (ctx (s back))
   =>
   (modify ?x (s go)))
(defrule seen
   (declare (salience -5))
   (ctx (s go))
   (cnt (c ?c))
   (item (id ?i) (v a))
   (not (item (id ?j&:(> ?j ?i)) (v a)))
   =>
   (printout t "seen " ?c " " ?i crlf))
(reset)
(run)
(facts)
(agenda)
(exit)
