;;; game-log.clp -- the decision log and the end of a game.
;;;
;;; Shared by the instant simulation and by host drivers that move a robot:
;;; whoever answers skill requests, each outcome is captured before the
;;; agent consumes it, and once the agent has digested it (IDLE or DONE
;;; again) a (decision) fact records the step with the agent's beliefs.
;;; The game ends with a (game-over) fact: the referee's clock ran out, the
;;; agent is DONE, or (a bug) the agent idles without deciding.
;;; Needs the agent's and the referee's templates.

(deftemplate log-pending
  (slot id (type INTEGER))
  (slot time (type NUMBER))
  (slot action (type SYMBOL))
  (slot target (type SYMBOL))
  (slot puck (type SYMBOL))
  (slot status (type SYMBOL))
  (slot light (type SYMBOL)))

(deftemplate decision
  "One committed action: game time when it ended, what and where, the
   outcome and light, and the agent's beliefs afterwards (one symbol per
   machine M1..M10: type belief, then +puck per loaded puck)."
  (slot n (type INTEGER))
  (slot time (type NUMBER))
  (slot action (type SYMBOL))
  (slot target (type SYMBOL))
  (slot puck (type SYMBOL))
  (slot status (type SYMBOL))
  (slot light (type SYMBOL))
  (slot holding (type SYMBOL))
  (multislot beliefs (type SYMBOL))
  (slot points (type INTEGER)))

(deffunction log-beliefs
  "The agent's machine beliefs, M1..M10, as symbols like T2_3+S0."
  ()
  (bind ?out (create$))
  (loop-for-count (?i 1 10)
    (do-for-fact ((?m machine)) (= ?m:index ?i)
      (bind ?b ?m:mtype)
      (progn$ (?l ?m:loaded-with) (bind ?b (sym-cat ?b "+" ?l)))
      (bind ?out (create$ ?out ?b))))
  ?out)

(defrule log-outcome
  "Capture an outcome with its request before execution monitoring
   retracts both."
  (declare (salience (+ ?*PRIORITY_EXEC* 10)))
  (skill-outcome (id ?id) (status ?status) (light ?l))
  (skill-request (id ?id) (name ?a) (target ?t) (puck ?x))
  (game-clock (time ?now))
  (not (log-pending (id ?id)))
  =>
  (assert (log-pending (id ?id) (time ?now) (action ?a) (target ?t)
                       (puck ?x) (status ?status) (light ?l))))

(defrule log-decision
  "The agent digested the outcome: log the decision with its new beliefs."
  (declare (salience ?*PRIORITY_LOG*))
  ?p <- (log-pending (id ?id) (time ?t) (action ?a) (target ?m)
          (puck ?x) (status ?st) (light ?l))
  (state IDLE|DONE)
  (holding ?h)
  (score (points ?pts))
  =>
  (retract ?p)
  (assert (decision (n ?id) (time ?t) (action ?a) (target ?m) (puck ?x)
                    (status ?st) (light ?l) (holding ?h)
                    (beliefs (log-beliefs)) (points ?pts))))

(defrule log-agent-done
  (declare (salience ?*PRIORITY_SIM*))
  (state DONE)
  (not (game-over))
  (game-clock (time ?now))
  =>
  (assert (game-over (reason done) (time ?now))))

(defrule log-deadlock
  "Idle, undecided and no game over: the agent has a hole (a bug)."
  (declare (salience ?*PRIORITY_DEADLOCK*))
  (state IDLE)
  (not (intent))
  (not (skill-request))
  (not (game-over))
  (game-clock (time ?now))
  =>
  (printout t "DEADLOCK at " ?now crlf)
  (assert (game-over (reason deadlock) (time ?now))))
