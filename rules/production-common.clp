;;; production-common.clp -- production steps every strategy shares.
;;;
;;; When IDLE: empty hands fetch a raw puck, a P goes to the active gate,
;;; and any other puck opens a (goto) target search that the strategy's
;;; candidate rules fill.  A puck nothing can use is discarded at the
;;; nearest recycling unit so the robot never stalls.

(deftemplate goto
  "Candidate targets for the held puck; only those of the highest machine
   priority seen so far (min-prio) stay in the list."
  (multislot machines (type SYMBOL))
  (slot min-prio (type INTEGER) (default 0)))

(deffunction nearest-of
  "The place closest to ?from; earlier places win ties."
  (?from $?places)
  (bind ?best nil)
  (bind ?best-d 0.0)
  (progn$ (?p ?places)
    (bind ?d (place-distance ?from ?p))
    (if (or (eq ?best nil) (< ?d ?best-d))
     then (bind ?best ?p) (bind ?best-d ?d)))
  ?best)

(defrule prod-get-s0
  "Empty hands: fetch a raw puck from the input storage."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE)
  (holding NONE)
  (not (input-storage empty))
  (not (intent))
  =>
  (assert (intent (action get-s0) (target INS))))

(defrule prod-deliver-p
  "A finished product goes to the active delivery gate."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE)
  (holding P)
  (active-gate ?gate)
  (not (intent))
  =>
  (assert (intent (action deliver) (target ?gate))))

(defrule prod-start-target-search
  "Holding an intermediate puck: collect candidate machines."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE)
  (holding S0|S1|S2)
  (not (goto))
  (not (intent))
  =>
  (assert (goto)))

(defrule prod-discard-unusable
  "No machine can use the held puck: drop it at the nearest recycling
   unit rather than idle forever."
  (declare (salience ?*PRIORITY_FALLBACK*))
  (state IDLE)
  ?g <- (goto (machines))
  (robot-at ?here)
  =>
  (retract ?g)
  (assert (intent (action discard) (target (nearest-of ?here R1 R2)))))

(defrule prod-discard-unknown-puck
  "A puck of unknown kind (a misread light, see wm-light-unknown): drop it
   at the nearest recycling unit."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE)
  (holding UNKNOWN)
  (not (intent))
  (robot-at ?here)
  =>
  (assert (intent (action discard) (target (nearest-of ?here R1 R2)))))
