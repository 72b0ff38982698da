; dynamic saliences over long lex/mea agendas: more distinct saliences than the host
; indexes salience groups for, then fewer; refresh-agenda and every-cycle re-sorting
(defglobal ?*s* = 0)
(defrule mk ?g <- (go ?n) =>
  (retract ?g)
  (loop-for-count (?i 1 ?n) (assert (item ?i (mod (* ?i 5) 6)))))
(defrule a (item ?i ?w) (item ?j&:(> ?j ?i) ?w) => (printout t "a " ?i " " ?j crlf))
(defrule b (declare (salience (mod ?*s* 20))) (item ?i ?) =>
  (bind ?*s* (+ ?*s* 1)) (printout t "b " ?i crlf))
(defrule c (declare (salience (- 0 (mod ?*s* 3)))) (item ?i 2) (item ?j&:(< ?j ?i) 2) =>
  (printout t "c " ?i " " ?j crlf))
(set-salience-evaluation when-activated)
(set-strategy lex)
(reset)
(assert (go 50))
(run 60)
(set-salience-evaluation when-defined)
(refresh-agenda)
(run 40)
(set-strategy mea)
(assert (item 200 2) (item 201 3))
(run 40)
(set-salience-evaluation every-cycle)
(run 30)
(set-salience-evaluation when-defined)
(set-strategy lex)
(run)
(exit)
