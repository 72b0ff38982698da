;;; worldmodel.clp -- the agent's beliefs and how perception updates them.
;;;
;;; Beliefs: a machine fact per machine (type belief, loaded pucks, junk,
;;; productions), (holding X) for the puck the robot carries (NONE, S0,
;;; S1, S2, P, JUNK from a machine, UNKNOWN), (robot-at PLACE), (s0-taken N) and (input-storage empty).
;;; Updates run after finish-puck-at ended FINAL: execution monitoring sets
;;; (state GOTO-FINAL), (goto-target M) and (light L).  First the light
;;; tells what the robot holds now (wm-light-*, which assert a wm-eval),
;;; then the evaluation narrows the machine's type (wm-green-*,
;;; wm-yellow-*, wm-flash-*), then the robot is IDLE again.

(deftemplate machine
  (slot name (type SYMBOL))
  (slot index (type INTEGER))           ; stable order for tie-breaks
  (slot mtype (type SYMBOL)
    (allowed-symbols T1_2_3 T1_2 T2_3 T1 T2 T3) (default T1_2_3))
  (multislot loaded-with (type SYMBOL) (allowed-symbols S0 S1 S2))
  (slot junk (type INTEGER) (default 0))
  (slot productions (type INTEGER) (default 0)))

(deftemplate wm-eval
  "One transport step to a machine, waiting to update the machine belief."
  (slot machine (type SYMBOL))
  (slot was-holding (type SYMBOL))
  (slot now-holding (type SYMBOL))
  (slot light (type SYMBOL)))

(deffacts agent-beliefs
  (state IDLE)
  (holding NONE)
  (robot-at INS)
  (s0-taken 0)
  (next-skill-id 1)
  (machine (name M1) (index 1)) (machine (name M2) (index 2))
  (machine (name M3) (index 3)) (machine (name M4) (index 4))
  (machine (name M5) (index 5)) (machine (name M6) (index 6))
  (machine (name M7) (index 7)) (machine (name M8) (index 8))
  (machine (name M9) (index 9)) (machine (name M10) (index 10))
  ;; approach poses: 0.605 m in front (south) of each machine centre
  (place (name M1) (x 1.68) (y 1.075)) (place (name M2) (x 3.92) (y 1.075))
  (place (name M3) (x 0.56) (y 2.195)) (place (name M4) (x 1.68) (y 2.195))
  (place (name M5) (x 2.8) (y 2.195)) (place (name M6) (x 3.92) (y 2.195))
  (place (name M7) (x 5.04) (y 2.195)) (place (name M8) (x 1.68) (y 3.315))
  (place (name M9) (x 3.92) (y 3.315)) (place (name M10) (x 5.04) (y 3.315))
  (place (name INS) (x 2.25) (y 4.9))
  (place (name D1) (x 3.15) (y 0.26)) (place (name D2) (x 2.8) (y 0.26))
  (place (name D3) (x 2.45) (y 0.26))
  (place (name R1) (x 0.2) (y 0.2)) (place (name R2) (x 5.4) (y 5.4))
  (place (name TST) (x 5.4) (y 0.2))
  )

;;; ---- the light -> what the robot holds now ----------------------------

(defrule wm-light-green
  "Green: the cycle completed; the n-th input makes the output of Tn."
  (declare (salience ?*PRIORITY_WM_LIGHT*))
  (state GOTO-FINAL) (goto-target ?name)
  ?h <- (holding ?was)
  (machine (name ?name) (mtype ?t) (loaded-with $?lw))
  ?l <- (light green)
  =>
  (bind ?now (green-output ?t (length$ ?lw)))
  (retract ?l ?h)
  (assert (holding ?now)
          (wm-eval (machine ?name) (was-holding ?was) (now-holding ?now)
                   (light green))))

(defrule wm-light-yellow
  "Yellow: the machine consumed the puck and needs more."
  (declare (salience ?*PRIORITY_WM_LIGHT*))
  (state GOTO-FINAL) (goto-target ?name)
  ?h <- (holding ?was)
  ?l <- (light yellow)
  =>
  (retract ?l ?h)
  (assert (holding NONE)
          (wm-eval (machine ?name) (was-holding ?was) (now-holding NONE)
                   (light yellow))))

(defrule wm-light-flashing
  "Yellow flashing: wrong input, the robot keeps its puck."
  (declare (salience ?*PRIORITY_WM_LIGHT*))
  (state GOTO-FINAL) (goto-target ?name)
  (holding ?was)
  ?l <- (light yellow-flashing)
  =>
  (retract ?l)
  (assert (wm-eval (machine ?name) (was-holding ?was) (now-holding ?was)
                   (light yellow-flashing))))

(deffunction light-from-belief
  "Green or flashing -- the two lights that leave a puck in the gripper --
   for bringing ?x to a machine believed ?belief holding ?lw, if the
   beliefs settle it: flashing when ?x is there already or every allowed
   type rejects it, green when every allowed type takes it (so it cannot
   have been rejected); unknown otherwise."
  (?belief ?lw ?x)
  (if (or (member$ ?x ?lw)
          (and (eq ?x S1) (eq ?belief T1))
          (and (eq ?x S2) (member$ ?belief (create$ T1 T2 T1_2))))
   then (return yellow-flashing))
  (if (every-type-takes ?belief ?x)
   then green
   else unknown))

(defrule wm-light-unknown-from-belief
  "The camera's light contradicts the gripper (see exec-seen-light), but
   the beliefs predict green or flashing for sure: believe them."
  (declare (salience (+ ?*PRIORITY_WM_LIGHT* 10)))
  (state GOTO-FINAL) (goto-target ?name)
  (holding ?x)
  ?l <- (light unknown)
  (machine (name ?name) (mtype ?t) (loaded-with $?lw))
  (test (neq (light-from-belief ?t ?lw ?x) unknown))
  =>
  (retract ?l)
  (assert (light (light-from-belief ?t ?lw ?x))))

(defrule wm-light-unknown
  "The camera's light contradicts the gripper and two lights fit (see
   exec-seen-light): the held puck's kind and the machine's contents are
   unknown.  Believe the machine empty (a later rejection shows what it
   holds) and get rid of the puck; the type belief stays, but an empty
   T2_3 is unknown again (the candidate rules expect a T2_3 to hold a puck)."
  (declare (salience ?*PRIORITY_WM_LIGHT*))
  (state GOTO-FINAL) (goto-target ?name)
  ?h <- (holding ?)
  ?l <- (light unknown)
  ?m <- (machine (name ?name) (mtype ?t))
  =>
  (retract ?l ?h)
  (modify ?m (mtype (if (eq ?t T2_3) then T1_2_3 else ?t)) (loaded-with))
  (assert (holding UNKNOWN)))

;;; ---- green: the type is the number of inputs consumed ------------------

(defrule wm-green-t1
  "Green on the first input: only a T1 converts a single puck."
  (declare (salience ?*PRIORITY_WM*))
  ?w <- (wm-eval (machine ?name) (light green) (now-holding S1))
  ?m <- (machine (name ?name) (loaded-with) (productions ?p))
  =>
  (retract ?w)
  (modify ?m (mtype T1) (productions (+ ?p 1))))

(defrule wm-green-t2
  "Green on the second input: a T2 made S2, the other input is junk."
  (declare (salience ?*PRIORITY_WM*))
  ?w <- (wm-eval (machine ?name) (light green) (now-holding S2))
  ?m <- (machine (name ?name) (loaded-with $?lw) (junk ?junk) (productions ?p))
  =>
  (retract ?w)
  (modify ?m (mtype T2) (loaded-with)
          (junk (+ ?junk (length$ ?lw))) (productions (+ ?p 1))))

(defrule wm-green-t3
  "Green on the third input: a T3 made P, two inputs are junk."
  (declare (salience ?*PRIORITY_WM*))
  ?w <- (wm-eval (machine ?name) (light green) (now-holding P))
  ?m <- (machine (name ?name) (loaded-with $?lw) (junk ?junk) (productions ?p))
  =>
  (retract ?w)
  (modify ?m (mtype T3) (loaded-with)
          (junk (+ ?junk (length$ ?lw))) (productions (+ ?p 1))))

;;; ---- yellow: consumed, the machine needs more inputs ---------------------

(defrule wm-yellow-s2-is-t3
  "Only a T3 consumes an S2."
  (declare (salience ?*PRIORITY_WM*))
  ?w <- (wm-eval (machine ?name) (light yellow) (was-holding S2))
  ?m <- (machine (name ?name) (loaded-with $?lw))
  =>
  (retract ?w)
  (modify ?m (mtype T3) (loaded-with (loaded-after T3 ?lw S2))))

(defrule wm-yellow-second-input-is-t3
  "A second input that still leaves the machine waiting: a T2 would be done."
  (declare (salience ?*PRIORITY_WM*))
  ?w <- (wm-eval (machine ?name) (light yellow) (was-holding ?x&S0|S1))
  ?m <- (machine (name ?name) (mtype ?t&:(mtype-may-be ?t T3))
          (loaded-with $?lw&:(> (length$ ?lw) 0)))
  =>
  (retract ?w)
  (modify ?m (mtype T3) (loaded-with (loaded-after T3 ?lw ?x))))

(defrule wm-yellow-first-input-unknown-is-t23
  "The first S0 or S1 consumed without output: T2 or T3."
  (declare (salience ?*PRIORITY_WM*))
  ?w <- (wm-eval (machine ?name) (light yellow) (was-holding ?x&S0|S1))
  ?m <- (machine (name ?name) (mtype T1_2_3|T2_3) (loaded-with))
  =>
  (retract ?w)
  (modify ?m (mtype T2_3) (loaded-with ?x)))

(defrule wm-yellow-first-input-t12-is-t2
  "Not a T3 and it waits for more: a T2."
  (declare (salience ?*PRIORITY_WM*))
  ?w <- (wm-eval (machine ?name) (light yellow) (was-holding ?x&S0|S1))
  ?m <- (machine (name ?name) (mtype T1_2) (loaded-with))
  =>
  (retract ?w)
  (modify ?m (mtype T2) (loaded-with ?x)))

(defrule wm-yellow-first-input-known
  "A known T2 or T3 takes its first input."
  (declare (salience ?*PRIORITY_WM*))
  ?w <- (wm-eval (machine ?name) (light yellow) (was-holding ?x&S0|S1))
  ?m <- (machine (name ?name) (mtype T2|T3) (loaded-with))
  =>
  (retract ?w)
  (modify ?m (loaded-with ?x)))

(defrule wm-yellow-contradicts-belief
  "Yellow for an S0/S1 where the belief says no: a T1 never waits, and a
   loaded machine that cannot be a T3 would have completed.  The belief was
   built on a misread light: the machine is a T2 (or T2/T3) holding ?x."
  (declare (salience ?*PRIORITY_WM*))
  ?w <- (wm-eval (machine ?name) (light yellow) (was-holding ?x&S0|S1))
  ?m <- (machine (name ?name) (mtype ?t) (loaded-with $?lw))
  (test (or (eq ?t T1)
            (and (> (length$ ?lw) 0) (not (mtype-may-be ?t T3)))))
  =>
  (retract ?w)
  (printout t "WARN yellow at " ?name " contradicts " ?t ": now "
              (if (mtype-may-be ?t T2) then T2 else T2_3) crlf)
  (modify ?m (mtype (if (mtype-may-be ?t T2) then T2 else T2_3))
          (loaded-with ?x)))

;;; ---- yellow flashing: the machine rejects the puck ------------------------

(defrule wm-flash-s1-empty-is-t1
  "Every T2 and T3 takes an S1 first: the machine is a T1."
  (declare (salience ?*PRIORITY_WM*))
  ?w <- (wm-eval (machine ?name) (light yellow-flashing) (was-holding S1))
  ?m <- (machine (name ?name) (mtype T1_2_3|T1_2) (loaded-with))
  =>
  (retract ?w)
  (modify ?m (mtype T1)))

(defrule wm-flash-s2-empty-is-t12
  "A T3 would take an S2: the unknown machine is T1 or T2."
  (declare (salience ?*PRIORITY_WM*))
  ?w <- (wm-eval (machine ?name) (light yellow-flashing) (was-holding S2))
  ?m <- (machine (name ?name) (mtype T1_2_3) (loaded-with))
  =>
  (retract ?w)
  (modify ?m (mtype T1_2)))

(defrule wm-flash-s2-loaded-t23-is-t2
  "A T3 would take an S2 it lacks: the loaded T2_3 is a T2."
  (declare (salience ?*PRIORITY_WM*))
  ?w <- (wm-eval (machine ?name) (light yellow-flashing) (was-holding S2))
  ?m <- (machine (name ?name) (mtype T2_3)
          (loaded-with $?lw&:(not (member$ S2 ?lw))))
  =>
  (retract ?w)
  (modify ?m (mtype T2)))

(defrule wm-flash-input-already-loaded
  "Every type the belief allows takes the puck (any type takes an S0), so
   rejecting it means that puck is already there: the beliefs had lost
   track of this machine (a reset, a misread light).  Only a T2 or T3 keeps
   pucks loaded."
  (declare (salience ?*PRIORITY_WM*))
  ?w <- (wm-eval (machine ?name) (light yellow-flashing) (was-holding ?x&S0|S1|S2))
  ?m <- (machine (name ?name) (mtype ?t)
          (loaded-with $?lw&:(not (member$ ?x ?lw))))
  (test (every-type-takes ?t ?x))
  =>
  (retract ?w)
  (bind ?holder (switch ?t (case T2 then T2) (case T3 then T3) (case T1_2 then T2)
                  (default T2_3)))
  (modify ?m (mtype ?holder) (loaded-with (loaded-after ?holder ?lw ?x))))

(defrule wm-flash-no-news
  "A rejection the beliefs already predicted (known type or puck already
   loaded) or cannot explain: nothing to learn."
  (declare (salience ?*PRIORITY_WM_CLEANUP*))
  ?w <- (wm-eval (light yellow-flashing))
  =>
  (retract ?w))

(defrule wm-eval-unexplained
  "Perception the beliefs cannot explain: forget what we believed about the
   machine's contents so later decisions do not build on it."
  (declare (salience ?*PRIORITY_WM_CLEANUP*))
  ?w <- (wm-eval (machine ?name) (light ?l&~yellow-flashing))
  ?m <- (machine (name ?name))
  =>
  (retract ?w)
  (printout t "WARN unexplained " ?l " at " ?name crlf)
  (modify ?m (mtype T1_2_3) (loaded-with)))

(defrule wm-goto-final-done
  "The transport step is evaluated: the robot is idle again."
  (declare (salience ?*PRIORITY_WM_CLEANUP*))
  ?s <- (state GOTO-FINAL)
  ?t <- (goto-target ?)
  (not (light ?))
  (not (wm-eval))
  =>
  (retract ?s ?t)
  (assert (state IDLE)))
