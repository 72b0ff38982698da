;;; sim.clp -- instant simulation: executes the agent's skill requests.
;;;
;;; Every skill succeeds unless a (fault (at-decision N) (kind K)) from the
;;; host names its request id.  A request becomes travel (straight line
;;; between approach poses at ROBOT_SPEED), then a referee action; the
;;; referee's answer becomes the skill outcome the agent sees.  The
;;; decision log and the end of the game are game-log.clp's business, so a
;;; host driver that moves a real or simulated robot shares them.

(deftemplate fault
  "Injected failure of the skill with request id at-decision:
   lose-puck (the puck is lost on the way; a fetched one too),
   drive-fail (the robot never gets there; a carried puck is lost)."
  (slot at-decision (type INTEGER))
  (slot kind (type SYMBOL) (allowed-symbols lose-puck drive-fail)))

(deftemplate sim-robot
  (slot at (type SYMBOL) (default INS))
  (slot travelled (type NUMBER) (default 0.0)))   ; metres so far

(deftemplate sim-step
  (slot id (type INTEGER))
  (slot phase (type SYMBOL) (allowed-symbols arrived asked))
  (slot failed (type SYMBOL) (allowed-symbols TRUE FALSE) (default FALSE)))

(deffacts sim-start
  (sim-robot))

(deffunction sim-referee-kind (?skill)
  (switch ?skill
    (case get-s0 then get-s0)
    (case finish-puck-at then load)
    (case deliver then deliver)
    (default discard)))

(defrule sim-travel
  "Drive to the skill's place; the clock runs while driving."
  (declare (salience ?*PRIORITY_SIM*))
  (skill-request (id ?id) (target ?to))
  (not (sim-step (id ?id)))
  (not (game-over))
  ?r <- (sim-robot (at ?from) (travelled ?m))
  ?c <- (game-clock (time ?now) (limit ?lim) (enabled ?on))
  =>
  (bind ?d (place-distance ?from ?to))
  (bind ?arrive (+ ?now (/ ?d ?*ROBOT_SPEED*)))
  (if (and (eq ?on TRUE) (> ?arrive ?lim))
   then (assert (game-over (reason time) (time ?lim)))
   else (modify ?c (time ?arrive))
        (modify ?r (at ?to) (travelled (+ ?m ?d)))
        (assert (sim-step (id ?id) (phase arrived)))))

(defrule sim-fault-drive-fail-empty-handed
  "A fetch that never reaches the storage: nothing to tell the referee."
  (declare (salience ?*PRIORITY_SIM*))
  ?s <- (sim-step (id ?id) (phase arrived))
  (fault (at-decision ?id) (kind drive-fail))
  (skill-request (id ?id) (name get-s0))
  =>
  (modify ?s (phase asked) (failed TRUE))
  (assert (rf-result (id ?id) (status ok))))

(defrule sim-fault-lose-puck
  "The puck is lost on the way (for a fetch: right after taking it)."
  (declare (salience ?*PRIORITY_SIM*))
  ?s <- (sim-step (id ?id) (phase arrived))
  (fault (at-decision ?id) (kind ?k))
  (skill-request (id ?id) (name ?a) (target ?t) (puck ?x))
  (test (or (eq ?k lose-puck) (neq ?a get-s0)))
  =>
  (modify ?s (phase asked) (failed TRUE))
  (assert (rf-action (id ?id) (kind lose) (target ?t)
                     (puck (if (eq ?a get-s0) then NONE else ?x)))))

(defrule sim-ask-referee
  (declare (salience ?*PRIORITY_SIM*))
  ?s <- (sim-step (id ?id) (phase arrived))
  (not (fault (at-decision ?id)))
  (skill-request (id ?id) (name ?a) (target ?t) (puck ?x))
  =>
  (modify ?s (phase asked))
  (assert (rf-action (id ?id) (kind (sim-referee-kind ?a)) (target ?t) (puck ?x))))

(defrule sim-report-outcome
  "The referee answered: tell the agent what its skill achieved."
  (declare (salience ?*PRIORITY_SIM*))
  (sim-step (id ?id) (phase asked) (failed ?failed))
  ?res <- (rf-result (id ?id) (status ?st&~late) (light ?l))
  =>
  (retract ?res)
  (bind ?status (if (or (eq ?failed TRUE) (eq ?st empty)) then FAILED else FINAL))
  (bind ?info (if (eq ?st empty) then storage-empty else none))
  (assert (skill-outcome (id ?id) (status ?status) (light ?l) (info ?info))))

