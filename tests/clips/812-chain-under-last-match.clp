; The last match of an alpha memory goes while the partial matches built on it form a
; chain (one child each) or a tree: agenda, firings and facts as in CLIPS.
(deftemplate job (slot id) (slot kind) (slot stage (default 0)))
(deftemplate mk (slot id))
(deffacts d (round 1) (job (id 1) (kind a)) (job (id 2) (kind b)) (job (id 3) (kind b))
  (job (id 4) (kind c)) (mk (id 3)))
(defrule ra ?j <- (job (id ?i) (kind a) (stage 0)) (round ?k) (not (mk (id ?i))) =>
  (printout t "ra " ?i crlf) (modify ?j (stage 1)))
(defrule rb ?j <- (job (id ?i) (kind b) (stage 0)) (round ?k) (exists (mk (id ?i))) =>
  (printout t "rb " ?i crlf) (modify ?j (stage 1)))
(defrule rb2 (job (id ?i) (kind b) (stage 0)) (round ?k) (job (id ?o&~?i) (stage ?s)) =>
  (printout t "rb2 " ?i " " ?o " " ?s crlf))
(defrule rc ?j <- (job (id ?i) (kind c) (stage ?s&:(< ?s 3))) (round ?k) =>
  (printout t "rc " ?i " " ?s crlf) (modify ?j (stage (+ ?s 1))))
(defrule next (declare (salience -10)) ?r <- (round ?k&:(< ?k 3)) =>
  (retract ?r) (assert (round (+ ?k 1))))
(reset)
(agenda)
(run 3)
(agenda)
(retract 1)
(agenda)
(assert (round 2))
(agenda)
(run 4)
(agenda)
(run)
(facts)
(agenda)
(exit)
