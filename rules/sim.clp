;;; sim.clp -- instant simulation: executes the agent's skill requests.
;;;
;;; Every skill succeeds unless a (fault (at-decision N) ...) from the host
;;; names its request id.  A request becomes travel (straight line between
;;; approach poses at ROBOT_SPEED), then a referee action; the referee's
;;; answer becomes the skill outcome the agent sees.  The simulation keeps
;;; the ground truth of what the robot carries ((sim-robot (puck))): the
;;; referee always sees the real puck, whatever the agent believes.  A skill
;;; that ends FAILED leaves the robot empty-handed (the puck was lost or
;;; grabbed in vain), except a failed drive, after which the robot still
;;; holds its puck and says so (info puck-held); the gripper's puck sensor
;;; (front IR) is also reported with every outcome at a machine (info
;;; puck-held / no-puck).  The decision log
;;; and the end of the game are game-log.clp's business, so a host driver
;;; that moves a real or simulated robot shares them.

(deftemplate fault
  "Injected disturbance of the skill with request id at-decision:
   lose-puck (the carried puck is lost on the way; a fetched one right
   after taking it), drive-fail (the goto fails: the robot never gets there;
   a carried puck stays in the gripper), grab-fail (fetching: the grab fails,
   nothing is taken), wrong-light (at a machine the camera reports another
   light than the machine shows; the machine acts as usual), drawn (the
   simulation picks one of the kinds that fit the skill from draw)."
  (slot at-decision (type INTEGER))
  (slot kind (type SYMBOL)
    (allowed-symbols lose-puck drive-fail grab-fail wrong-light drawn))
  (slot draw (type INTEGER) (default 0)))

(deftemplate sim-robot
  (slot at (type SYMBOL) (default INS))
  (slot travelled (type NUMBER) (default 0.0))   ; metres so far
  (slot puck (type SYMBOL) (default NONE)))      ; what it really carries

(deftemplate sim-step
  (slot id (type INTEGER))
  (slot phase (type SYMBOL) (allowed-symbols arrived asked))
  ;; KEPT: failed, the robot still holds its puck
  (slot failed (type SYMBOL) (allowed-symbols TRUE FALSE KEPT) (default FALSE))
  (slot misread (type INTEGER) (default 0)))  ; wrong light: 1 or 2, see sim-misread-light

(deffacts sim-start
  (sim-robot))

(deffunction sim-referee-kind (?skill)
  (switch ?skill
    (case get-s0 then get-s0)
    (case finish-puck-at then load)
    (case deliver then deliver)
    (case get-junk then take-junk)
    (case recycle then recycle)
    (default discard)))

(deffunction sim-fault-kind
  "The fault that strikes skill ?skill with request id ?id, or none.  A
   drawn fault takes the ?draw-th of the kinds that fit the skill."
  (?id ?skill)
  (bind ?kind none)
  (do-for-fact ((?f fault)) (= ?f:at-decision ?id)
    (bind ?kind ?f:kind)
    (if (eq ?kind drawn)
     then (bind ?fits (switch ?skill
                        (case get-s0 then (create$ lose-puck drive-fail grab-fail))
                        (case get-junk then (create$ lose-puck drive-fail grab-fail))
                        (case finish-puck-at then (create$ lose-puck drive-fail wrong-light))
                        (default (create$ lose-puck drive-fail))))
          (bind ?kind (nth$ (+ 1 (mod ?f:draw (length$ ?fits))) ?fits))))
  ?kind)

(deffunction sim-fault-misread
  "Which misreading (1 or 2) a wrong light is, from the fault's draw."
  (?id)
  (bind ?variant 1)
  (do-for-fact ((?f fault)) (= ?f:at-decision ?id)
    (bind ?variant (+ 1 (mod (div ?f:draw 6) 2))))
  ?variant)

(deffunction sim-misread-light
  "The light a camera confuses with ?light: neighbouring signals only, a
   steady with a flashing yellow and a green with a yellow (variant 1: green,
   2: flashing for a yellow).  Green and flashing yellow differ in colour and
   blink, so they are never confused.  Variant 0: read correctly."
  (?light ?variant)
  (if (= ?variant 0)
   then ?light
   else (switch ?light
          (case green then yellow)
          (case yellow-flashing then yellow)
          (case yellow then (if (= ?variant 1) then green else yellow-flashing))
          (default ?light))))

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

(defrule sim-act
  "Arrived: the skill meets the world.  The referee is asked with the puck
   the robot really carries; faults and an empty or unexpectedly full
   gripper make the skill fail."
  (declare (salience ?*PRIORITY_SIM*))
  ?s <- (sim-step (id ?id) (phase arrived))
  (skill-request (id ?id) (name ?a) (target ?t))
  (sim-robot (puck ?held))
  =>
  (bind ?fault (sim-fault-kind ?id ?a))
  (bind ?fetch (or (eq ?a get-s0) (eq ?a get-junk)))
  (if (and (not ?fetch) (eq ?held NONE))
   then ;; nothing to carry (the agent misjudged what it holds): fail
        (modify ?s (phase asked) (failed TRUE))
        (assert (rf-result (id ?id) (status ok)))
   else
   (if (and ?fetch (neq ?held NONE))
    then ;; a puck the agent did not know of blocks the gripper: the
         ;; behaviour layer pushes it aside (lost) and reports failure
         (modify ?s (phase asked) (failed TRUE))
         (assert (rf-action (id ?id) (kind lose) (target ?t) (puck ?held)))
    else
    (switch ?fault
      (case drive-fail then
        (modify ?s (phase asked) (failed (if ?fetch then TRUE else KEPT)))
        (assert (rf-result (id ?id) (status ok))))
      (case lose-puck then
        (modify ?s (phase asked) (failed TRUE))
        (assert (rf-action (id ?id) (kind lose) (target ?t) (puck ?held))))
      (case grab-fail then
        (modify ?s (phase asked) (failed TRUE))
        (assert (rf-result (id ?id) (status ok))))
      (case wrong-light then
        (modify ?s (phase asked) (misread (sim-fault-misread ?id)))
        (assert (rf-action (id ?id) (kind (sim-referee-kind ?a)) (target ?t) (puck ?held))))
      (default
        (modify ?s (phase asked))
        (assert (rf-action (id ?id) (kind (sim-referee-kind ?a)) (target ?t) (puck ?held))))))))

(defrule sim-report-outcome
  "The referee answered: tell the agent what its skill achieved, with the
   puck sensor's reading at a machine."
  (declare (salience ?*PRIORITY_SIM*))
  (sim-step (id ?id) (phase asked) (failed ?failed) (misread ?misread))
  (skill-request (id ?id) (name ?a))
  ?res <- (rf-result (id ?id) (status ?st&~late) (light ?l) (puck ?after))
  ?r <- (sim-robot (puck ?held))
  =>
  (retract ?res)
  (bind ?kept (eq ?failed KEPT))
  (bind ?fail (or (eq ?failed TRUE) ?kept (eq ?st empty)))
  (bind ?status (if ?fail then FAILED else FINAL))
  (bind ?now (if ?kept then ?held else (if ?fail then NONE else ?after)))
  (modify ?r (puck ?now))
  (bind ?info (if (eq ?st empty)
               then (if (eq ?a get-junk) then no-junk else storage-empty)
               else (if ?kept
                     then puck-held
                     else (if (and (not ?fail) (eq ?a finish-puck-at))
                           then (if (eq ?now NONE) then no-puck else puck-held)
                           else none))))
  (assert (skill-outcome (id ?id) (status ?status)
                         (light (sim-misread-light ?l ?misread)) (info ?info))))
