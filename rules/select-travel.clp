;;; select-travel.clp -- our travel-aware commitment (beyond the paper):
;;; among the candidates of the highest machine priority, take the one
;;; nearest to the robot; equal distances fall back to name order.

(deffunction nearest-machine
  "The machine among ?names closest to ?from; ties by smallest index."
  (?from $?names)
  (bind ?best nil)
  (bind ?best-d 0.0)
  (bind ?best-i 0)
  (progn$ (?n ?names)
    (bind ?d (place-distance ?from ?n))
    (do-for-fact ((?m machine)) (eq ?m:name ?n)
      (if (or (eq ?best nil) (< ?d ?best-d)
              (and (= ?d ?best-d) (< ?m:index ?best-i)))
       then (bind ?best ?n) (bind ?best-d ?d) (bind ?best-i ?m:index))))
  ?best)

(defrule prod-select-nearest
  (declare (salience ?*PRIORITY_SELECT*))
  (state IDLE)
  (robot-at ?here)
  ?g <- (goto (machines $?ms&:(> (length$ ?ms) 0)))
  =>
  (retract ?g)
  (assert (intent (action finish-puck-at) (target (nearest-machine ?here ?ms)))))
