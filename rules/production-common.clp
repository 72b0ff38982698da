;;; production-common.clp -- production steps every strategy shares.
;;;
;;; When IDLE: empty hands fetch a raw puck, a P goes to the active gate,
;;; and any other puck opens a (goto) target search that the strategy's
;;; candidate rules fill.  A puck nothing can use is discarded at the
;;; nearest recycling unit so the robot never stalls.  Junk left at a
;;; machine by a production is taken to a recycling unit before the next
;;; raw puck is fetched: it scores and comes back as a raw puck.

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

(deffunction nearest-junk
  "The machine with junk closest to ?from; lower index wins ties."
  (?from)
  (bind ?best nil)
  (bind ?best-d 0.0)
  (bind ?best-i 0)
  (do-for-all-facts ((?m machine)) (> ?m:junk 0)
    (bind ?d (place-distance ?from ?m:name))
    (if (or (eq ?best nil) (< ?d ?best-d)
            (and (= ?d ?best-d) (< ?m:index ?best-i)))
     then (bind ?best ?m:name) (bind ?best-d ?d) (bind ?best-i ?m:index)))
  ?best)

(defrule prod-get-s0
  "Empty hands: fetch a raw puck from the input storage (known junk goes
   first, see prod-get-junk)."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE)
  (holding NONE)
  (not (input-storage empty))
  (not (intent))
  =>
  (assert (intent (action get-s0) (target INS))))

(defrule prod-get-junk
  "Empty hands and junk lying at a machine: recycling it scores (2012: +3
   per T2 production, +6 per T3) and gives a raw puck back, so it comes
   before the input storage.  The nearest junk first.  An executor that
   cannot carry junk yet asserts (no-recycling)."
  (declare (salience ?*PRIORITY_RECYCLE*))
  (state IDLE)
  (holding NONE)
  (not (no-recycling))
  (exists (machine (junk ?j&:(> ?j 0))))
  (robot-at ?here)
  (not (intent))
  =>
  (assert (intent (action get-junk) (target (nearest-junk ?here)))))

(defrule prod-recycle
  "Holding junk: to the nearest recycling unit, which returns an S0."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE)
  (holding JUNK)
  (robot-at ?here)
  (not (intent))
  =>
  (assert (intent (action recycle) (target (nearest-of ?here R1 R2)))))

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
