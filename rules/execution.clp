;;; execution.clp -- execution monitoring: skill requests and outcomes.
;;;
;;; Production commits by asserting an (intent). Execution turns it into a
;;; numbered (skill-request) for the behaviour layer (the simulation or the
;;; robot driver) and waits in state EXEC.  The executor answers with a
;;; (skill-outcome) of the same id: FINAL (with the light seen at a
;;; machine) or FAILED.  A failure aborts the step: the robot believes it
;;; holds nothing, unless the executor's puck sensor says the puck is still
;;; in the gripper (info puck-held: kept), and is IDLE again, ready for the
;;; next best action.
;;; Recycling (2012 rules): get-junk takes a junk puck at a machine
;;; (holding JUNK), recycle brings it to a recycling unit, which turns it
;;; back into S0 (holding S0).

(deftemplate intent
  (slot action (type SYMBOL)
    (allowed-symbols get-s0 finish-puck-at deliver discard get-junk recycle
      feed collect))
  (slot target (type SYMBOL)))

(deftemplate skill-request
  (slot id (type INTEGER))
  (slot name (type SYMBOL)
    (allowed-symbols get-s0 finish-puck-at deliver discard get-junk recycle
      feed collect))
  (slot target (type SYMBOL))
  (slot puck (type SYMBOL) (default NONE)))

(deftemplate skill-outcome
  (slot id (type INTEGER))
  (slot status (type SYMBOL) (allowed-symbols FINAL FAILED))
  (slot light (type SYMBOL) (default none)
    (allowed-symbols none green yellow yellow-flashing red off))
  (slot info (type SYMBOL) (default none)))

(defrule exec-request-skill
  "Commit: number the intent and hand it to the behaviour layer."
  (declare (salience ?*PRIORITY_EXEC*))
  ?s <- (state IDLE)
  ?i <- (intent (action ?a) (target ?t))
  ?n <- (next-skill-id ?id)
  (holding ?puck)
  =>
  (retract ?s ?i ?n)
  (assert (state EXEC) (next-skill-id (+ ?id 1))
          (skill-request (id ?id) (name ?a) (target ?t) (puck ?puck))))

(defrule exec-get-s0-final
  (declare (salience ?*PRIORITY_EXEC*))
  ?s <- (state EXEC)
  ?r <- (skill-request (id ?id) (name get-s0) (target ?t))
  ?o <- (skill-outcome (id ?id) (status FINAL))
  ?h <- (holding ?)
  ?c <- (s0-taken ?n)
  ?p <- (robot-at ?)
  =>
  (retract ?s ?r ?o ?h ?c ?p)
  (assert (state IDLE) (holding S0) (s0-taken (+ ?n 1)) (robot-at ?t)))

(defrule exec-get-s0-storage-empty
  "The input storage has no more raw pucks."
  (declare (salience ?*PRIORITY_EXEC*))
  ?s <- (state EXEC)
  ?r <- (skill-request (id ?id) (name get-s0) (target ?t))
  ?o <- (skill-outcome (id ?id) (status FAILED) (info storage-empty))
  ?p <- (robot-at ?)
  =>
  (retract ?s ?r ?o ?p)
  (assert (state IDLE) (input-storage empty) (robot-at ?t)))

(deffunction exec-seen-light
  "The light to believe after a transport step, from the camera's light and
   the gripper's puck sensor (info puck-held or no-puck; none: no reading).
   Only yellow leaves the gripper empty: an empty gripper with another
   light means the camera erred and the machine consumed the puck (yellow).
   A held puck with yellow means the camera erred too, but green (holding
   the output) and flashing (holding the input) both fit: unknown."
  (?machine ?light ?info)
  (if (and (eq ?info no-puck) (neq ?light yellow))
   then (printout t "WARN light " ?light " at " ?machine
                    " but the gripper is empty: read as yellow" crlf)
        (return yellow))
  (if (and (eq ?info puck-held) (eq ?light yellow))
   then (printout t "WARN light yellow at " ?machine
                    " but the gripper holds a puck: light unknown" crlf)
        (return unknown))
  ?light)

(defrule exec-get-junk-final
  "Took a junk puck at a machine: one less lies there."
  (declare (salience ?*PRIORITY_EXEC*))
  ?s <- (state EXEC)
  ?r <- (skill-request (id ?id) (name get-junk) (target ?m))
  ?o <- (skill-outcome (id ?id) (status FINAL))
  ?h <- (holding ?)
  ?f <- (machine (name ?m) (junk ?j))
  ?p <- (robot-at ?)
  =>
  (retract ?s ?r ?o ?h ?p)
  (modify ?f (junk (if (> ?j 0) then (- ?j 1) else 0)))
  (assert (state IDLE) (holding JUNK) (robot-at ?m)))

(defrule exec-get-junk-none
  "No junk where the agent believed some: believe none is there (before
   exec-failed-abort, which handles other failed fetches of junk)."
  (declare (salience (+ ?*PRIORITY_EXEC* 1)))
  ?s <- (state EXEC)
  ?r <- (skill-request (id ?id) (name get-junk) (target ?m))
  ?o <- (skill-outcome (id ?id) (status FAILED) (info no-junk))
  ?h <- (holding ?)
  ?f <- (machine (name ?m))
  ?p <- (robot-at ?)
  =>
  (retract ?s ?r ?o ?h ?p)
  (modify ?f (junk 0))
  (assert (state IDLE) (holding NONE) (robot-at ?m)))

(defrule exec-recycle-final
  "The recycling unit turned the junk back into a raw puck, now held."
  (declare (salience ?*PRIORITY_EXEC*))
  ?s <- (state EXEC)
  ?r <- (skill-request (id ?id) (name recycle) (target ?t))
  ?o <- (skill-outcome (id ?id) (status FINAL))
  ?h <- (holding ?)
  ?p <- (robot-at ?)
  =>
  (retract ?s ?r ?o ?h ?p)
  (assert (state IDLE) (holding S0) (robot-at ?t)))

(defrule exec-finish-puck-final
  "Arrived with the puck: the world model reads the light (checked against
   the gripper's puck sensor)."
  (declare (salience ?*PRIORITY_EXEC*))
  ?s <- (state EXEC)
  ?r <- (skill-request (id ?id) (name finish-puck-at) (target ?m))
  ?o <- (skill-outcome (id ?id) (status FINAL) (light ?l) (info ?info))
  ?p <- (robot-at ?)
  =>
  (retract ?s ?r ?o ?p)
  (assert (state GOTO-FINAL) (goto-target ?m) (light (exec-seen-light ?m ?l ?info))
          (robot-at ?m)))

(defrule exec-puck-handed-over
  "Delivered or discarded: the hands are empty."
  (declare (salience ?*PRIORITY_EXEC*))
  ?s <- (state EXEC)
  ?r <- (skill-request (id ?id) (name deliver|discard) (target ?t))
  ?o <- (skill-outcome (id ?id) (status FINAL))
  ?h <- (holding ?)
  ?p <- (robot-at ?)
  =>
  (retract ?s ?r ?o ?h ?p)
  (assert (state IDLE) (holding NONE) (robot-at ?t)))

(defrule exec-get-s0-failed
  "Fetching failed: the puck may have been taken and lost on the way, so
   the agent counts it as taken and holds nothing."
  (declare (salience ?*PRIORITY_EXEC*))
  ?s <- (state EXEC)
  ?r <- (skill-request (id ?id) (name get-s0) (target ?t))
  ?o <- (skill-outcome (id ?id) (status FAILED) (info ~storage-empty))
  ?h <- (holding ?)
  ?c <- (s0-taken ?n)
  ?p <- (robot-at ?)
  =>
  (retract ?s ?r ?o ?h ?c ?p)
  (assert (state IDLE) (holding NONE) (s0-taken (+ ?n 1)) (robot-at ?t)))

(defglobal ?*KEPT_TRIES* = 2)   ; failures in a row that keep the puck

(deffacts execution-start
  (kept-failures 0))

(defrule exec-failed-still-holding
  "The skill failed on the way, but the gripper still holds the puck (the
   executor's puck sensor: info puck-held): abort, keep the puck and the
   beliefs, go idle; the next decision uses the puck.  After KEPT_TRIES
   such failures in a row the step is aborted as any other (the puck is
   believed lost): whatever keeps failing is not tried forever."
  (declare (salience (+ ?*PRIORITY_EXEC* 1)))
  ?s <- (state EXEC)
  ?r <- (skill-request (id ?id) (name ~get-s0&~get-junk))
  ?o <- (skill-outcome (id ?id) (status FAILED) (info puck-held))
  (holding ~NONE)
  ?k <- (kept-failures ?n&:(< ?n ?*KEPT_TRIES*))
  =>
  (retract ?s ?r ?o ?k)
  (assert (state IDLE) (kept-failures (+ ?n 1))))

(defrule exec-kept-failures-over
  "A skill ended FINAL, or a failure left the hands empty: the next kept
   failure counts from zero again."
  (declare (salience (+ ?*PRIORITY_EXEC* 2)))
  (skill-outcome (status ?st) (info ?info))
  (test (or (eq ?st FINAL) (neq ?info puck-held)))
  ?k <- (kept-failures ?n&:(> ?n 0))
  =>
  (retract ?k)
  (assert (kept-failures 0)))

(defrule exec-failed-abort
  "The behaviour layer gave up carrying a puck (or fetching junk): abort, believe the puck is
   gone (machine beliefs stay: it was lost on the way), go idle."
  (declare (salience ?*PRIORITY_EXEC*))
  ?s <- (state EXEC)
  ?r <- (skill-request (id ?id) (name ~get-s0) (target ?t))
  ?o <- (skill-outcome (id ?id) (status FAILED))
  ?h <- (holding ?)
  ?p <- (robot-at ?)
  =>
  (retract ?s ?r ?o ?h ?p)
  (assert (state IDLE) (holding NONE) (robot-at ?t)))

(defrule exec-nothing-left
  "Empty hands, an empty input storage and no junk to recycle: the agent
   is done."
  (declare (salience ?*PRIORITY_DONE*))
  ?s <- (state IDLE)
  (holding NONE)
  (input-storage empty)
  (not (machine (junk ?j&:(> ?j 0))))
  (not (intent))
  =>
  (retract ?s)
  (assert (state DONE)))

(defrule exec-nothing-left-unrecyclable
  "The same for an executor that cannot carry junk (no-recycling): junk
   left at machines does not keep the agent busy."
  (declare (salience ?*PRIORITY_DONE*))
  ?s <- (state IDLE)
  (holding NONE)
  (input-storage empty)
  (no-recycling)
  (not (intent))
  =>
  (retract ?s)
  (assert (state DONE)))
