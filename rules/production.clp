;;; production.clp -- the paper's production process: next best target.
;;;
;;; Each rule recognises one situation in which the held puck is useful at
;;; a machine and merges that machine into the (goto) candidates with the
;;; situation's machine priority (globals PRIO_* in utils.clp): a higher
;;; priority replaces the list, an equal one joins it, a lower one is
;;; ignored (min-prio).  Completing a higher valued sub-goal ranks above
;;; starting one, production above exploration.  A select-*.clp file then
;;; commits to one of the remaining candidates.

(deffunction awaits-s1
  "TRUE if a machine with this belief and load waits for an S1 that a T1
   could make: a T2 or T2_3 holding just an S0, or a started T3 without S1.
   (A pattern predicate, not a test CE, so it is re-evaluated whenever any
   machine belief changes.)"
  (?mtype $?loaded)
  (and (not (member$ S1 ?loaded))
       (or (and (member$ ?mtype (create$ T2 T2_3))
                (= (length$ ?loaded) 1) (member$ S0 ?loaded))
           (and (eq ?mtype T3) (> (length$ ?loaded) 0)))))

(defrule prod-complete-p
  "The held puck is the last input a T3 lacks: a P."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE) (holding ?x&S0|S1|S2)
  (machine (name ?n) (mtype T3)
    (loaded-with $?lw&:(= (length$ ?lw) 2)&:(not (member$ ?x ?lw))))
  ?g <- (goto (machines $?ms&:(not (member$ ?n ?ms)))
              (min-prio ?mp&:(<= ?mp ?*PRIO_COMPLETE_P*)))
  =>
  (modify ?g (machines (merge ?mp ?*PRIO_COMPLETE_P* ?n ?ms))
             (min-prio ?*PRIO_COMPLETE_P*)))

(defrule prod-complete-s2
  "The held puck is the input a loaded T2 lacks: an S2."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE) (holding ?x&S0|S1)
  (machine (name ?n) (mtype T2) (loaded-with ?y&~?x))
  ?g <- (goto (machines $?ms&:(not (member$ ?n ?ms)))
              (min-prio ?mp&:(<= ?mp ?*PRIO_COMPLETE_S2*)))
  =>
  (modify ?g (machines (merge ?mp ?*PRIO_COMPLETE_S2* ?n ?ms))
             (min-prio ?*PRIO_COMPLETE_S2*)))

(defrule prod-s0-t23-s1
  "The paper's example: S0 to a T2_3 holding an S1 makes an S2 or
   advances a T3, and tells which."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE) (holding S0)
  (machine (name ?n) (mtype T2_3) (loaded-with S1))
  ?g <- (goto (machines $?ms&:(not (member$ ?n ?ms)))
              (min-prio ?mp&:(<= ?mp ?*PRIO_RESOLVE_T23*)))
  =>
  (modify ?g (machines (merge ?mp ?*PRIO_RESOLVE_T23* ?n ?ms))
             (min-prio ?*PRIO_RESOLVE_T23*)))

(defrule prod-s1-t23-s0
  "S1 to a T2_3 holding an S0: the mirror of prod-s0-t23-s1."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE) (holding S1)
  (machine (name ?n) (mtype T2_3) (loaded-with S0))
  ?g <- (goto (machines $?ms&:(not (member$ ?n ?ms)))
              (min-prio ?mp&:(<= ?mp ?*PRIO_RESOLVE_T23*)))
  =>
  (modify ?g (machines (merge ?mp ?*PRIO_RESOLVE_T23* ?n ?ms))
             (min-prio ?*PRIO_RESOLVE_T23*)))

(defrule prod-t3-progress
  "Second input of a T3 that already holds one other input."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE) (holding ?x&S0|S1|S2)
  (machine (name ?n) (mtype T3) (loaded-with ?y&~?x))
  ?g <- (goto (machines $?ms&:(not (member$ ?n ?ms)))
              (min-prio ?mp&:(<= ?mp ?*PRIO_T3_PROGRESS*)))
  =>
  (modify ?g (machines (merge ?mp ?*PRIO_T3_PROGRESS* ?n ?ms))
             (min-prio ?*PRIO_T3_PROGRESS*)))

(defrule prod-s0-feed-t1
  "An S1 is awaited somewhere: turn the S0 into one at a known T1."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE) (holding S0)
  (machine (name ?n) (mtype T1))
  (exists (machine (mtype ?t) (loaded-with $?l&:(awaits-s1 ?t ?l))))
  ?g <- (goto (machines $?ms&:(not (member$ ?n ?ms)))
              (min-prio ?mp&:(<= ?mp ?*PRIO_FEED_S1*)))
  =>
  (modify ?g (machines (merge ?mp ?*PRIO_FEED_S1* ?n ?ms))
             (min-prio ?*PRIO_FEED_S1*)))

(defrule prod-t2-start
  "First input of an empty known T2."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE) (holding S0|S1)
  (machine (name ?n) (mtype T2) (loaded-with))
  ?g <- (goto (machines $?ms&:(not (member$ ?n ?ms)))
              (min-prio ?mp&:(<= ?mp ?*PRIO_T2_START*)))
  =>
  (modify ?g (machines (merge ?mp ?*PRIO_T2_START* ?n ?ms))
             (min-prio ?*PRIO_T2_START*)))

(defrule prod-t3-start-s2
  "An S2 opens an empty known T3."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE) (holding S2)
  (machine (name ?n) (mtype T3) (loaded-with))
  ?g <- (goto (machines $?ms&:(not (member$ ?n ?ms)))
              (min-prio ?mp&:(<= ?mp ?*PRIO_T3_START_S2*)))
  =>
  (modify ?g (machines (merge ?mp ?*PRIO_T3_START_S2* ?n ?ms))
             (min-prio ?*PRIO_T3_START_S2*)))

(defrule prod-t3-start
  "An S0 or S1 opens an empty known T3."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE) (holding S0|S1)
  (machine (name ?n) (mtype T3) (loaded-with))
  ?g <- (goto (machines $?ms&:(not (member$ ?n ?ms)))
              (min-prio ?mp&:(<= ?mp ?*PRIO_T3_START*)))
  =>
  (modify ?g (machines (merge ?mp ?*PRIO_T3_START* ?n ?ms))
             (min-prio ?*PRIO_T3_START*)))

(defrule prod-s0-t1
  "S0 to a known T1 makes an S1."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE) (holding S0)
  (machine (name ?n) (mtype T1))
  ?g <- (goto (machines $?ms&:(not (member$ ?n ?ms)))
              (min-prio ?mp&:(<= ?mp ?*PRIO_T1*)))
  =>
  (modify ?g (machines (merge ?mp ?*PRIO_T1* ?n ?ms))
             (min-prio ?*PRIO_T1*)))

(defrule prod-s2-explore-t23
  "S2 to a loaded T2_3: yellow means T3, flashing means T2 (puck kept)."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE) (holding S2)
  (machine (name ?n) (mtype T2_3) (loaded-with $?lw&:(not (member$ S2 ?lw))))
  ?g <- (goto (machines $?ms&:(not (member$ ?n ?ms)))
              (min-prio ?mp&:(<= ?mp ?*PRIO_EXPLORE_T23*)))
  =>
  (modify ?g (machines (merge ?mp ?*PRIO_EXPLORE_T23* ?n ?ms))
             (min-prio ?*PRIO_EXPLORE_T23*)))

(defrule prod-explore-unknown
  "Exploration: any puck to a machine of unknown type teaches something."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE) (holding S0|S1|S2)
  (machine (name ?n) (mtype T1_2_3) (loaded-with))
  ?g <- (goto (machines $?ms&:(not (member$ ?n ?ms)))
              (min-prio ?mp&:(<= ?mp ?*PRIO_EXPLORE*)))
  =>
  (modify ?g (machines (merge ?mp ?*PRIO_EXPLORE* ?n ?ms))
             (min-prio ?*PRIO_EXPLORE*)))

(defrule prod-explore-t12
  "Exploration: S0 or S1 tells a T1_2 machine's type."
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE) (holding S0|S1)
  (machine (name ?n) (mtype T1_2) (loaded-with))
  ?g <- (goto (machines $?ms&:(not (member$ ?n ?ms)))
              (min-prio ?mp&:(<= ?mp ?*PRIO_EXPLORE*)))
  =>
  (modify ?g (machines (merge ?mp ?*PRIO_EXPLORE* ?n ?ms))
             (min-prio ?*PRIO_EXPLORE*)))
