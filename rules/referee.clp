;;; referee.clp -- the LLSF 2012 game model (ground truth), self-contained.
;;;
;;; Knows the hidden machine types, what each machine holds, the raw puck
;;; supply, the clock and the score.  Whoever moves the robot (the instant
;;; simulation in sim.clp, or a host driver) advances (game-clock) by the
;;; travel time and asserts an (rf-action); the referee answers with an
;;; (rf-result) of the same id, applies processing time to the clock and
;;; scores.  Setup facts the host asserts before (run): (rf-machine (name)
;;; (type)) x10, and optionally (rf-times ...), (s0-supply N),
;;; (active-gate Dk), (game-clock ...); missing ones get defaults.
;;;
;;; Recycling (2012 rulebook, robocup-logistics/rcll-rulebook, first commit,
;;; rulebook2012.tex: "Recycling Unit" and the scoring table): a T2's
;;; production leaves one consumed puck (junk) at the machine, a T3's two.
;;; A robot may take junk from a machine (rf-action take-junk) and bring it
;;; to a recycling unit R1/R2 (rf-action recycle): "The recycling unit
;;; processes all supplied loading carriers back to raw-material (S0) within
;;; 2 seconds", so the robot leaves with an S0 it can use again.  Points:
;;; "Clean up a polluted machine (M2 or M3) by recycling all of the consumed
;;; loading carriers.  Partial recycling (M3) will not be rewarded": +3 for
;;; the junk of a T2 production, +6 once both junk pucks of a T3 production
;;; are recycled (counted per machine: any two of its junk make a pair).
;;; Delivered pucks leave the game ("cannot be recycled").  The rulebook
;;; turns any puck brought to a recycling unit into S0; here only junk is
;;; recycled (rf-recycle-refused): the agent discards a puck it cannot use
;;; (unknown after a misread light) rather than recycle it.  The referee knows which machine the junk a robot carries came from
;;; (rf-junk-held), so rf-action names the robot (1 when one robot plays).

(defglobal ?*RF_SALIENCE* = 500)

(deftemplate rf-machine
  (slot name (type SYMBOL))
  (slot type (type SYMBOL) (allowed-symbols T1 T2 T3))
  (multislot loaded-with (type SYMBOL) (allowed-symbols S0 S1 S2))
  (slot junk (type INTEGER) (default 0))          ; junk pucks lying there
  (slot recycled (type INTEGER) (default 0))      ; of a T3 pair, recycled so far
  (slot productions (type INTEGER) (default 0)))

(deftemplate rf-times
  "Seconds a machine works after the last input, per type, and per
   consumed intermediate input."
  (slot t1 (type NUMBER) (default 5.5))
  (slot t2 (type NUMBER) (default 20.0))
  (slot t3 (type NUMBER) (default 50.0))
  (slot per-input (type NUMBER) (default 2.0))
  (slot recycle (type NUMBER) (default 2.0)))

(deftemplate rf-storage
  (slot s0 (type INTEGER)))

(deftemplate game-clock
  (slot time (type NUMBER) (default 0.0))
  (slot limit (type NUMBER) (default 900.0))
  (slot enabled (type SYMBOL) (allowed-symbols TRUE FALSE) (default TRUE)))

(deftemplate score
  (slot points (type INTEGER) (default 0))
  (slot s1 (type INTEGER) (default 0))
  (slot s2 (type INTEGER) (default 0))
  (slot p (type INTEGER) (default 0))
  (slot delivered (type INTEGER) (default 0))
  (slot wrong-gate (type INTEGER) (default 0))
  (slot lost (type INTEGER) (default 0))
  (slot discarded (type INTEGER) (default 0))
  (slot recycled (type INTEGER) (default 0)))     ; junk pucks recycled

(deftemplate rf-action
  (slot id (type INTEGER))
  (slot kind (type SYMBOL)
    (allowed-symbols get-s0 load deliver discard lose take-junk recycle))
  (slot target (type SYMBOL))
  (slot puck (type SYMBOL) (default NONE))
  (slot robot (type INTEGER) (default 1)))

(deftemplate rf-junk-held
  "Robot ?robot carries a junk puck taken from machine ?from."
  (slot robot (type INTEGER))
  (slot from (type SYMBOL)))

(deftemplate rf-result
  (slot id (type INTEGER))
  (slot status (type SYMBOL) (allowed-symbols ok empty late))
  (slot light (type SYMBOL) (default none))
  (slot puck (type SYMBOL) (default NONE))   ; what the robot holds after
  (slot wait (type NUMBER) (default 0.0)))   ; processing time spent there

(deftemplate game-over
  (slot reason (type SYMBOL) (allowed-symbols time done deadlock))
  (slot time (type NUMBER)))

(deffacts referee-boot
  (rf-boot)
  (score))

(deffunction rf-inputs (?type)
  (switch ?type
    (case T1 then (create$ S0))
    (case T2 then (create$ S0 S1))
    (case T3 then (create$ S0 S1 S2))
    (default (create$))))

(deffunction rf-output (?type)
  (switch ?type (case T1 then S1) (case T2 then S2) (case T3 then P)
    (default NONE)))

(deffunction rf-process-time (?type ?t1 ?t2 ?t3)
  (switch ?type (case T1 then ?t1) (case T2 then ?t2) (case T3 then ?t3)
    (default 0.0)))

(deffunction rf-junk-per-production
  "Junk pucks one production leaves: the inputs but the converted one."
  (?type)
  (switch ?type (case T2 then 1) (case T3 then 2) (default 0)))

(deffunction rf-recycle-points
  "2012 points for recycling all junk of one production: T2 +3, T3 +6."
  (?type)
  (switch ?type (case T2 then 3) (case T3 then 6) (default 0)))

(deffunction rf-output-points
  "2012 points for producing: S2 +4, P +12."
  (?type)
  (switch ?type (case T2 then 4) (case T3 then 12) (default 0)))

;;; ---- defaults for setup facts the host left out ----------------------

(defrule rf-default-times
  (declare (salience (+ ?*RF_SALIENCE* 10)))
  (rf-boot) (not (rf-times))
  =>
  (assert (rf-times)))

(defrule rf-default-supply
  (declare (salience (+ ?*RF_SALIENCE* 10)))
  (rf-boot) (not (s0-supply ?))
  =>
  (assert (s0-supply 20)))

(defrule rf-default-gate
  (declare (salience (+ ?*RF_SALIENCE* 10)))
  (rf-boot) (not (active-gate ?))
  =>
  (assert (active-gate D1)))

(defrule rf-default-clock
  (declare (salience (+ ?*RF_SALIENCE* 10)))
  (rf-boot) (not (game-clock))
  =>
  (assert (game-clock)))

(defrule rf-boot-done
  "Fill the input storage once the setup is complete."
  (declare (salience (+ ?*RF_SALIENCE* 5)))
  ?b <- (rf-boot)
  (s0-supply ?n)
  =>
  (retract ?b)
  (assert (rf-storage (s0 ?n))))

;;; ---- the input storage ------------------------------------------------

(defrule rf-get-s0
  (declare (salience ?*RF_SALIENCE*))
  ?a <- (rf-action (id ?id) (kind get-s0))
  ?s <- (rf-storage (s0 ?n&:(> ?n 0)))
  =>
  (retract ?a)
  (modify ?s (s0 (- ?n 1)))
  (assert (rf-result (id ?id) (status ok) (puck S0))))

(defrule rf-get-s0-empty
  (declare (salience ?*RF_SALIENCE*))
  ?a <- (rf-action (id ?id) (kind get-s0))
  (rf-storage (s0 0))
  =>
  (retract ?a)
  (assert (rf-result (id ?id) (status empty))))

;;; ---- production machines ------------------------------------------------

(defrule rf-load-wrong-input
  "Not an input of this type, or already there: yellow flashing, the robot
   keeps its puck."
  (declare (salience ?*RF_SALIENCE*))
  ?a <- (rf-action (id ?id) (kind load) (target ?m) (puck ?x))
  (rf-machine (name ?m) (type ?t) (loaded-with $?lw))
  (test (or (not (member$ ?x (rf-inputs ?t))) (member$ ?x ?lw)))
  =>
  (retract ?a)
  (assert (rf-result (id ?id) (status ok) (light yellow-flashing) (puck ?x))))

(defrule rf-load-consume
  "A needed input, but not the last: consumed (yellow) after per-input s."
  (declare (salience ?*RF_SALIENCE*))
  ?a <- (rf-action (id ?id) (kind load) (target ?m) (puck ?x))
  ?f <- (rf-machine (name ?m) (type ?t) (loaded-with $?lw))
  (test (and (member$ ?x (rf-inputs ?t)) (not (member$ ?x ?lw))
             (< (+ 1 (length$ ?lw)) (length$ (rf-inputs ?t)))))
  (rf-times (per-input ?w))
  ?c <- (game-clock (time ?now) (limit ?lim) (enabled ?on))
  =>
  (retract ?a)
  (if (and (eq ?on TRUE) (> (+ ?now ?w) ?lim))
   then (assert (rf-result (id ?id) (status late) (puck ?x))
                (game-over (reason time) (time ?lim)))
   else (modify ?f (loaded-with ?lw ?x))
        (modify ?c (time (+ ?now ?w)))
        (assert (rf-result (id ?id) (status ok) (light yellow) (wait ?w)))))

(defrule rf-load-complete
  "The last missing input: after the processing time the machine converts
   it to its output (green); the earlier inputs become junk."
  (declare (salience ?*RF_SALIENCE*))
  ?a <- (rf-action (id ?id) (kind load) (target ?m) (puck ?x))
  ?f <- (rf-machine (name ?m) (type ?t) (loaded-with $?lw) (junk ?j)
          (productions ?n))
  (test (and (member$ ?x (rf-inputs ?t)) (not (member$ ?x ?lw))
             (= (+ 1 (length$ ?lw)) (length$ (rf-inputs ?t)))))
  (rf-times (t1 ?t1) (t2 ?t2) (t3 ?t3))
  ?c <- (game-clock (time ?now) (limit ?lim) (enabled ?on))
  ?s <- (score (points ?pts) (s1 ?s1) (s2 ?s2) (p ?p))
  =>
  (retract ?a)
  (bind ?w (rf-process-time ?t ?t1 ?t2 ?t3))
  (if (and (eq ?on TRUE) (> (+ ?now ?w) ?lim))
   then (assert (rf-result (id ?id) (status late) (puck ?x))
                (game-over (reason time) (time ?lim)))
   else (bind ?out (rf-output ?t))
        (modify ?f (loaded-with) (junk (+ ?j (length$ ?lw)))
                (productions (+ ?n 1)))
        (modify ?c (time (+ ?now ?w)))
        (modify ?s (points (+ ?pts (rf-output-points ?t)))
                (s1 (+ ?s1 (if (eq ?out S1) then 1 else 0)))
                (s2 (+ ?s2 (if (eq ?out S2) then 1 else 0)))
                (p (+ ?p (if (eq ?out P) then 1 else 0))))
        (assert (rf-result (id ?id) (status ok) (light green) (puck ?out)
                           (wait ?w)))))

;;; ---- delivery, recycling, losses ----------------------------------------

(defrule rf-deliver-active-gate
  (declare (salience ?*RF_SALIENCE*))
  ?a <- (rf-action (id ?id) (kind deliver) (target ?g) (puck P))
  (active-gate ?g)
  ?s <- (score (points ?pts) (delivered ?d))
  =>
  (retract ?a)
  (modify ?s (points (+ ?pts 5)) (delivered (+ ?d 1)))
  (assert (rf-result (id ?id) (status ok))))

(defrule rf-deliver-other
  "A gate that is not active, or a puck that is not a P: no points."
  (declare (salience ?*RF_SALIENCE*))
  ?a <- (rf-action (id ?id) (kind deliver) (target ?g) (puck ?x))
  (active-gate ?active)
  (test (or (neq ?g ?active) (neq ?x P)))
  ?s <- (score (wrong-gate ?w))
  =>
  (retract ?a)
  (modify ?s (wrong-gate (+ ?w 1)))
  (assert (rf-result (id ?id) (status ok))))

(defrule rf-discard
  (declare (salience ?*RF_SALIENCE*))
  ?a <- (rf-action (id ?id) (kind discard))
  ?s <- (score (discarded ?d))
  =>
  (retract ?a)
  (modify ?s (discarded (+ ?d 1)))
  (assert (rf-result (id ?id) (status ok))))

(defrule rf-junk-leaves-robot
  "Junk lost, dropped or driven into a gate: that robot carries none now
   (the machine it came from cannot be cleaned up with it)."
  (declare (salience (+ ?*RF_SALIENCE* 1)))
  (rf-action (kind lose|discard|deliver) (puck JUNK) (robot ?r))
  ?h <- (rf-junk-held (robot ?r))
  =>
  (retract ?h))

(defrule rf-lose-carried-puck
  (declare (salience ?*RF_SALIENCE*))
  ?a <- (rf-action (id ?id) (kind lose) (puck ?x&~NONE))
  ?s <- (score (lost ?l))
  =>
  (retract ?a)
  (modify ?s (lost (+ ?l 1)))
  (assert (rf-result (id ?id) (status ok))))

(defrule rf-lose-fetched-puck
  "Lost right after taking it from the input storage."
  (declare (salience ?*RF_SALIENCE*))
  ?a <- (rf-action (id ?id) (kind lose) (target ?t) (puck NONE))
  (not (rf-machine (name ?t)))
  ?st <- (rf-storage (s0 ?n))
  ?s <- (score (lost ?l))
  =>
  (retract ?a)
  (if (> ?n 0)
   then (modify ?st (s0 (- ?n 1)))
        (modify ?s (lost (+ ?l 1))))
  (assert (rf-result (id ?id) (status ok))))

(defrule rf-lose-fetched-junk
  "Lost right after taking junk from a machine: it is gone from there."
  (declare (salience ?*RF_SALIENCE*))
  ?a <- (rf-action (id ?id) (kind lose) (target ?m) (puck NONE))
  ?f <- (rf-machine (name ?m) (junk ?j))
  ?s <- (score (lost ?l))
  =>
  (retract ?a)
  (if (> ?j 0)
   then (modify ?f (junk (- ?j 1)))
        (modify ?s (lost (+ ?l 1))))
  (assert (rf-result (id ?id) (status ok))))

;;; ---- recycling (2012 rulebook, see the header) ---------------------------

(defrule rf-take-junk
  "A robot with empty hands takes a junk puck lying at a machine."
  (declare (salience ?*RF_SALIENCE*))
  ?a <- (rf-action (id ?id) (kind take-junk) (target ?m) (robot ?r))
  ?f <- (rf-machine (name ?m) (junk ?j&:(> ?j 0)))
  =>
  (retract ?a)
  (modify ?f (junk (- ?j 1)))
  (assert (rf-junk-held (robot ?r) (from ?m))
          (rf-result (id ?id) (status ok) (puck JUNK))))

(defrule rf-take-junk-none
  "No junk at that place: nothing to take."
  (declare (salience (- ?*RF_SALIENCE* 1)))
  ?a <- (rf-action (id ?id) (kind take-junk))
  =>
  (retract ?a)
  (assert (rf-result (id ?id) (status empty))))

(defrule rf-recycle-junk
  "Junk brought to a recycling unit: back to S0 after the recycling time;
   the last junk of a production scores that production's recycling."
  (declare (salience ?*RF_SALIENCE*))
  ?a <- (rf-action (id ?id) (kind recycle) (target R1|R2) (puck JUNK) (robot ?r))
  ?h <- (rf-junk-held (robot ?r) (from ?m))
  ?f <- (rf-machine (name ?m) (type ?t) (recycled ?n))
  (rf-times (recycle ?w))
  ?c <- (game-clock (time ?now) (limit ?lim) (enabled ?on))
  ?s <- (score (points ?pts) (recycled ?rc))
  =>
  (retract ?a)
  (if (and (eq ?on TRUE) (> (+ ?now ?w) ?lim))
   then (assert (rf-result (id ?id) (status late) (puck JUNK))
                (game-over (reason time) (time ?lim)))
   else (retract ?h)
        (bind ?all (>= (+ ?n 1) (rf-junk-per-production ?t)))
        (modify ?f (recycled (if ?all then 0 else (+ ?n 1))))
        (modify ?s (points (+ ?pts (if ?all then (rf-recycle-points ?t) else 0)))
                (recycled (+ ?rc 1)))
        (modify ?c (time (+ ?now ?w)))
        (assert (rf-result (id ?id) (status ok) (puck S0) (wait ?w)))))

(defrule rf-recycle-refused
  "Anything but junk that robot took from a machine: nothing recycled (the
   agent discards other pucks, see the header)."
  (declare (salience (- ?*RF_SALIENCE* 1)))
  ?a <- (rf-action (id ?id) (kind recycle))
  =>
  (retract ?a)
  (assert (rf-result (id ?id) (status empty))))
