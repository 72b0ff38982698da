;;; select-paper.clp -- the paper's commitment: among the candidates of the
;;; highest machine priority, take the first machine in name order
;;; (M1 < M2 < ... < M10), so ties never depend on agenda order.

(deffunction first-by-index
  "The machine among ?names with the smallest index."
  ($?names)
  (bind ?best nil)
  (bind ?best-i 0)
  (progn$ (?n ?names)
    (do-for-fact ((?m machine)) (eq ?m:name ?n)
      (if (or (eq ?best nil) (< ?m:index ?best-i))
       then (bind ?best ?n) (bind ?best-i ?m:index))))
  ?best)

(defrule prod-select-by-name
  (declare (salience ?*PRIORITY_SELECT*))
  (state IDLE)
  ?g <- (goto (machines $?ms&:(> (length$ ?ms) 0)))
  =>
  (retract ?g)
  (assert (intent (action finish-puck-at) (target (first-by-index ?ms)))))
