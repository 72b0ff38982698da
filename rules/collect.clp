;;; collect.clp -- a robot on the field leaves a working T3 and comes back for the P.
;;;
;;; A T3 works 50 s on its last input.  The instant simulation charges that wait
;;; to the clock; a robot on the field need not stand there meanwhile.  `run`
;;; loads this file after the agent (the instant simulation and the image do
;;; not): a puck for a known T3 goes in by a `feed` skill, which leaves the
;;; puck under the machine's light once the machine works on it (outcome FINAL,
;;; light yellow, info processing).  The robot then believes the machine full
;;; (all three inputs, so no candidate rule picks it) with its two junk pucks
;;; and the P lying there, (output-at M P), and does the next best thing: the
;;; junk right there first (recycled into a raw puck it goes on with), and once
;;; its hands are empty it comes back to `collect` the P (the skill waits there
;;; for green).  A team member keeps its claim on M until then (team-agent.clp,
;;; team-done-with), so nobody else loads M or takes what lies there.

(defrule feed-last-input-of-t3
  "A puck for a known T3: feed it, and leave if it completes the T3.  Also
   when the robot believes inputs missing: a feed the machine only takes ends
   as finish-puck-at does, and a teammate's puck (or one lost there by a
   robot passing by) may have completed the machine unknown to this robot
   (seed 80 with one robot killed: an S0 believed the second input was the
   third, and the robot stood 61 s under the light)."
  (declare (salience (+ ?*PRIORITY_EXEC* 1)))
  (state IDLE)
  ?i <- (intent (action finish-puck-at) (target ?m))
  (holding ?x)
  (machine (name ?m) (mtype T3)
    (loaded-with $?lw&:(not (member$ ?x ?lw))))
  (not (output-at ?m ?))
  =>
  (modify ?i (action feed)))

(defrule feed-s2
  "An S2 for a machine that may be a T3: feed it too.  Only a T3 takes an
   S2, so a machine that starts working on it is a T3 completed (the feed
   leaves, as above); any other light ends the feed as finish-puck-at does.
   On a lossy link a robot often does not know that a machine is a T3 whose
   other two inputs a teammate loaded (seed 4 with 10 % loss: robot 3 stood
   62 s at M6, 50 s of them while the T3 worked)."
  (declare (salience (+ ?*PRIORITY_EXEC* 1)))
  (state IDLE)
  ?i <- (intent (action finish-puck-at) (target ?m))
  (holding S2)
  (machine (name ?m) (mtype ?t&~T3&:(mtype-may-be ?t T3))
    (loaded-with $?lw&:(not (member$ S2 ?lw))))
  (not (output-at ?m ?))
  =>
  (modify ?i (action feed)))

(defrule exec-feed-left-processing
  "The T3 works on the last input, left there: it made a P (collected later)
   and its other two inputs are junk (whatever the robot believed loaded)."
  (declare (salience (+ ?*PRIORITY_EXEC* 1)))
  ?s <- (state EXEC)
  ?r <- (skill-request (id ?id) (name feed) (target ?m))
  ?o <- (skill-outcome (id ?id) (status FINAL) (info processing))
  ?h <- (holding ?x)
  ?f <- (machine (name ?m) (loaded-with $?lw) (junk ?j) (productions ?n))
  ?p <- (robot-at ?)
  =>
  (retract ?s ?r ?o ?h ?p)
  (modify ?f (mtype T3) (loaded-with S0 S1 S2) (junk (+ ?j 2))
          (productions (+ ?n 1)))
  (assert (state IDLE) (holding NONE) (robot-at ?m) (output-at ?m P)))

(defrule exec-feed-final
  "Any other light after a feed: read it as after finish-puck-at (the
   beliefs were wrong; the world model sorts it out)."
  (declare (salience ?*PRIORITY_EXEC*))
  ?s <- (state EXEC)
  ?r <- (skill-request (id ?id) (name feed) (target ?m))
  ?o <- (skill-outcome (id ?id) (status FINAL) (light ?l) (info ?info&~processing))
  ?p <- (robot-at ?)
  =>
  (retract ?s ?r ?o ?p)
  (assert (state GOTO-FINAL) (goto-target ?m) (light (exec-seen-light ?m ?l ?info))
          (robot-at ?m)))

(defrule exec-output-waits-there
  "The puck was brought to a machine that stayed green and took nothing: an
   output lies under its light (the spot holds one puck), left by a feed,
   another robot's or this robot's own, perhaps of a robot that died.  Only
   a completed T3 leaves one there (feed-last-input-of-t3, feed-s2): believe
   it full, with its two junk pucks and a P to collect, and keep the puck
   for other work (before exec-failed-still-holding, which would bring it
   there again and again: kill-one seed 79, a dead robot's P under a T3 the
   others fed in vain for the rest of the game)."
  (declare (salience (+ ?*PRIORITY_EXEC* 2)))
  ?s <- (state EXEC)
  ?r <- (skill-request (id ?id) (name finish-puck-at|feed) (target ?m))
  ?o <- (skill-outcome (id ?id) (status FAILED) (info output-waits))
  ?f <- (machine (name ?m) (junk ?j) (productions ?n))
  ?p <- (robot-at ?)
  =>
  (retract ?s ?r ?o ?p)
  (printout t "WARN an output waits at " ?m crlf)
  (if (not (any-factp ((?c output-at)) (eq (nth$ 1 ?c:implied) ?m)))
   then (modify ?f (mtype T3) (loaded-with S0 S1 S2) (junk (+ ?j 2))
                (productions (+ ?n 1)))
        (assert (output-at ?m P))
   else (modify ?f (mtype T3) (loaded-with S0 S1 S2)))
  (assert (state IDLE) (robot-at ?m)))

(defrule prod-collect-output
  "Hands empty and an output waits at a machine: fetch it, once the junk
   there is no longer the nearer work (the first junk puck is taken right
   after feeding, while the machine still works).  A robot elsewhere fetches
   it whatever junk lies there: its product is ready and its claim keeps the
   machine from the team (seed 46's team: a P lay 4 minutes at a T3 while a
   teammate with an S2 waited for a T3)."
  (declare (salience (+ ?*PRIORITY_RECYCLE* 1)))
  (state IDLE)
  (holding NONE)
  (output-at ?m ?)
  (machine (name ?m) (junk ?j))
  (not (robot-at ?m&:(>= ?j 2)))
  (not (intent))
  =>
  (assert (intent (action collect) (target ?m))))

(defrule collect-not-done
  "An output still waits: the robot is not done."
  (declare (salience ?*PRIORITY_EXEC*))
  ?s <- (state DONE)
  (holding NONE)
  (output-at ? ?)
  =>
  (retract ?s)
  (assert (state IDLE)))

(defrule exec-collect-final
  "Took the output: the machine is empty again."
  (declare (salience ?*PRIORITY_EXEC*))
  ?s <- (state EXEC)
  ?r <- (skill-request (id ?id) (name collect) (target ?m))
  ?o <- (skill-outcome (id ?id) (status FINAL))
  ?c <- (output-at ?m ?out)
  ?h <- (holding ?)
  ?f <- (machine (name ?m))
  ?p <- (robot-at ?)
  =>
  (retract ?s ?r ?o ?c ?h ?p)
  (modify ?f (loaded-with))
  (assert (state IDLE) (holding ?out) (robot-at ?m)))

(defrule exec-collect-none
  "No output turned up: believe none is there and the machine empty (before
   exec-failed-abort, which keeps the belief after a failure on the way)."
  (declare (salience (+ ?*PRIORITY_EXEC* 1)))
  ?s <- (state EXEC)
  ?r <- (skill-request (id ?id) (name collect) (target ?m))
  ?o <- (skill-outcome (id ?id) (status FAILED) (info no-output))
  ?c <- (output-at ?m ?)
  ?h <- (holding ?)
  ?f <- (machine (name ?m))
  ?p <- (robot-at ?)
  =>
  (retract ?s ?r ?o ?c ?h ?p)
  (printout t "WARN no output at " ?m crlf)
  (modify ?f (loaded-with))
  (assert (state IDLE) (holding NONE) (robot-at ?m)))
