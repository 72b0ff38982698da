;;; team-agent.clp -- the agent as a member of a team (after team.clp).
;;;
;;; The robot commits only to what it holds: an intent at a shared place (a
;;; machine, a delivery gate, a recycling unit) is claimed first (state
;;; TEAM-CLAIM); once held the skill request goes out as usual.  If another
;;; robot has the place, the intent is dropped and the robot waits (state
;;; TEAM-WAIT) until the place is free, then decides again with what it has
;;; learned meanwhile.  When the skill's outcome is digested, the robot tells
;;; the team what it now believes of that machine (news) and then releases
;;; the claim; the others take the news into their own machine beliefs.  So
;;; two robots never work one machine, and no robot carries an input chosen
;;; on beliefs another robot was about to change.

(defglobal
  ?*PRIORITY_TEAM_AGENT* = 105   ; above execution (100)
  ?*TEAM_NEWS_COPIES* = 2)       ; news is sent this often: a lost copy costs nothing

(deffunction team-resource-p (?action ?x)
  "A shared place for this action: a gate, a machine, and a recycling unit to
   recycle at (one robot works a unit at a time; a discard needs none).  Not
   the input storage: each robot takes its raw pucks at its own spot there,
   and what the team took is told by news (below).  Claimed as one place, it
   kept robots waiting for each other at the start (lossy link: 20 of 28
   stalls in 100 seeds began at t=0)."
  (or (member$ ?x (create$ D1 D2 D3 M1 M2 M3 M4 M5 M6 M7 M8 M9 M10))
      (and (eq ?action recycle) (member$ ?x (create$ R1 R2)))))

(defrule team-claim-first
  "An intent at a shared place this robot does not hold now: claim the place
   before committing (a want left from the last skill there, not released
   yet, is not a hold)."
  (declare (salience ?*PRIORITY_TEAM_AGENT*))
  ?s <- (state IDLE)
  (intent (action ?a) (target ?x&:(team-resource-p ?a ?x)))
  (team-clock (now ?t))
  (not (team-claim (resource ?x) (until ?u&:(> ?u ?t))))
  =>
  (retract ?s)
  (assert (state TEAM-CLAIM))
  (if (not (any-factp ((?w team-want)) (eq ?w:resource ?x)))
   then (assert (team-want (resource ?x)))))

(defrule team-claim-held
  "The place is ours: commit (execution turns the intent into a request)."
  (declare (salience ?*PRIORITY_TEAM_AGENT*))
  ?s <- (state TEAM-CLAIM)
  (intent (target ?x))
  (team-clock (now ?t))
  (team-claim (resource ?x) (until ?u&:(> ?u ?t)))
  =>
  (retract ?s)
  (assert (state IDLE)))

(defrule team-claim-busy
  "Another robot has the place: drop the intent and wait for the place."
  (declare (salience ?*PRIORITY_TEAM_AGENT*))
  ?s <- (state TEAM-CLAIM)
  ?i <- (intent (target ?x))
  ?w <- (team-want (resource ?x))
  (team-self (id ?me))
  (team-clock (now ?t))
  (team-vote (resource ?x) (holder ~?me) (until ?u&:(> ?u ?t)))
  =>
  (retract ?s ?i ?w)
  (assert (state TEAM-WAIT) (team-waiting ?x)))

(defrule team-wait-starts
  "The robot claims a place or found it busy: its wait counts from the first
   claim since its last skill (claims and waits for one place after another
   add up; a claim can last when robots' requests keep splitting the votes)."
  (declare (salience ?*PRIORITY_TEAM_AGENT*))
  (state TEAM-CLAIM|TEAM-WAIT)
  (team-clock (now ?t))
  (not (team-wait-since ?))
  =>
  (assert (team-wait-since ?t)))

(defrule team-idle-starts
  "The robot claims a place or found it busy: team-idle-since counts all its
   waits since its last skill (the switches to other work below do not
   restart it, unlike team-wait-since)."
  (declare (salience ?*PRIORITY_TEAM_AGENT*))
  (state TEAM-CLAIM|TEAM-WAIT)
  (team-clock (now ?t))
  (not (team-idle-since ?))
  =>
  (assert (team-idle-since ?t)))

(deftemplate team-blocked
  "A place this robot could not drive to ?*TEAM_UNREACHED_TRIES* times in a
   row (a dead teammate's body in its approach stays there): it is avoided
   as if another robot held it, until game time `until`."
  (slot resource (type SYMBOL))
  (slot until (type NUMBER)))

(deffunction team-free-of
  "The places of ?places no other robot holds now (nor blocked for this one)."
  ($?places)
  (bind ?me 0)
  (do-for-fact ((?f team-self)) TRUE (bind ?me ?f:id))
  (bind ?now 0.0)
  (do-for-fact ((?c team-clock)) TRUE (bind ?now ?c:now))
  (bind ?free (create$))
  (progn$ (?p ?places)
    (if (not (or (any-factp ((?v team-vote))
                   (and (eq ?v:resource ?p) (neq ?v:holder ?me) (> ?v:until ?now)))
                 (any-factp ((?b team-blocked))
                   (and (eq ?b:resource ?p) (> ?b:until ?now)))))
     then (bind ?free (create$ ?free ?p))))
  ?free)

(deffunction team-unblocked-of
  "The places of ?places this robot can drive to, as far as it knows (not
   blocked for it; see 'a place the robot cannot drive to')."
  ($?places)
  (bind ?now 0.0)
  (do-for-fact ((?c team-clock)) TRUE (bind ?now ?c:now))
  (bind ?open (create$))
  (progn$ (?p ?places)
    (if (not (any-factp ((?b team-blocked))
               (and (eq ?b:resource ?p) (> ?b:until ?now))))
     then (bind ?open (create$ ?open ?p))))
  ?open)

(deffunction team-nearest-of
  "The place of ?places nearest to ?from (earlier places win ties)."
  (?from $?places)
  (bind ?best nil)
  (bind ?best-d 0.0)
  (progn$ (?p ?places)
    (bind ?d (place-distance ?from ?p))
    (if (or (eq ?best nil) (< ?d ?best-d))
     then (bind ?best ?p) (bind ?best-d ?d)))
  ?best)

(defrule team-select-free-candidate
  "Another robot holds some of the candidate machines for the held puck: take
   the nearest of the others, rather than wait for the held one (before the
   strategy's own selection; if all are held the robot claims one and waits)."
  (declare (salience (+ ?*PRIORITY_SELECT* 1)))
  (state IDLE)
  ?g <- (goto (machines $?ms&:(> (length$ ?ms) 1)))
  (robot-at ?here)
  (test (< 0 (length$ (team-free-of ?ms)) (length$ ?ms)))
  =>
  (retract ?g)
  (assert (intent (action finish-puck-at)
                  (target (team-nearest-of ?here (team-free-of ?ms))))))

(defrule team-claim-busy-other-unit
  "The recycling unit is another robot's: recycle at the other one, if free,
   rather than wait (before team-claim-busy)."
  (declare (salience (+ ?*PRIORITY_TEAM_AGENT* 1)))
  (state TEAM-CLAIM)
  ?i <- (intent (action recycle) (target ?x))
  ?w <- (team-want (resource ?x))
  (team-self (id ?me))
  (team-clock (now ?t))
  (team-vote (resource ?x) (holder ~?me) (until ?u&:(> ?u ?t)))
  (test (member$ ?x (create$ R1 R2)))
  =>
  (bind ?y (if (eq ?x R1) then R2 else R1))
  (if (not (any-factp ((?v team-vote))
             (and (eq ?v:resource ?y) (neq ?v:holder ?me) (> ?v:until ?t))))
   then (retract ?w)
        (modify ?i (target ?y))
        (assert (team-want (resource ?y)))))

(deftemplate skill-abort
  "The executor is to stop skill id at once and report it FAILED."
  (slot id (type INTEGER)))

(defrule team-hold-lapsed
  "Execution monitoring: the hold on the place of the running skill ran out
   (its renewals were lost), so another robot may get it: the robot must not
   act there any more.  The skill is aborted (the executor reports it FAILED;
   execution resets the beliefs as for any failure) and the robot decides anew."
  (declare (salience ?*PRIORITY_TEAM_AGENT*))
  (state EXEC)
  (skill-request (id ?id) (name ?a) (target ?x&:(team-resource-p ?a ?x)))
  (not (skill-outcome (id ?id)))
  (not (skill-abort (id ?id)))
  (team-clock (now ?t))
  (not (team-claim (resource ?x) (until ?u&:(> ?u ?t))))
  =>
  (printout t "WARN hold on " ?x " lapsed at " ?t ": skill " ?id " aborted" crlf)
  (assert (skill-abort (id ?id))))

(defrule team-abort-over
  "The aborted skill's outcome is digested."
  (declare (salience ?*PRIORITY_TEAM_AGENT*))
  ?a <- (skill-abort (id ?id))
  (not (skill-request (id ?id)))
  =>
  (retract ?a))

(defrule team-wait-over
  "The place is free again: decide anew."
  (declare (salience ?*PRIORITY_TEAM_AGENT*))
  ?s <- (state TEAM-WAIT)
  ?w <- (team-waiting ?x)
  (team-self (id ?me))
  (team-clock (now ?t))
  (not (team-vote (resource ?x) (holder ~?me) (until ?u&:(> ?u ?t))))
  (not (team-blocked (resource ?x) (until ?b&:(> ?b ?t))))
  =>
  (retract ?s ?w)
  (assert (state IDLE)))

(defrule team-wait-ends-with-skill
  "A skill started: the robot no longer waits (team-wait-since counts the
   time since its last skill in which it only found busy places)."
  (declare (salience ?*PRIORITY_TEAM_AGENT*))
  (state EXEC)
  ?b <- (team-wait-since ?)
  =>
  (retract ?b))

(defrule team-idle-ends-with-skill
  "A skill started: team-idle-since (waits in all since the last skill) ends."
  (declare (salience ?*PRIORITY_TEAM_AGENT*))
  (state EXEC)
  ?b <- (team-idle-since ?)
  =>
  (retract ?b))

(defglobal ?*TEAM_WAIT_HOLDING_S* = 20)   ; s: longest wait with a puck and a product out

(defrule team-wait-breaks-hold-cycle
  "Waiting with a puck in hand while this robot's product lies at a machine
   it holds (collect.clp): the robot waited on may be waiting for that very
   machine, with its hands full too.  After a while the robot lets go of the
   puck (discard) and goes for its product, which frees its machine."
  (declare (salience ?*PRIORITY_TEAM_AGENT*))
  ?s <- (state TEAM-WAIT)
  ?w <- (team-waiting ?x)
  ?b <- (team-wait-since ?t0)
  (team-clock (now ?t&:(>= ?t (+ ?t0 ?*TEAM_WAIT_HOLDING_S*))))
  (holding ~NONE)
  (output-at ? ?)
  (robot-at ?here)
  (test (> (length$ (team-unblocked-of R1 R2)) 0))
  =>
  (retract ?s ?w ?b)
  (printout t "WARN waited " (- ?t ?t0) " s for " ?x " with a product out: discard" crlf)
  (assert (state IDLE)
          (intent (action discard)
                  (target (nearest-of ?here (team-unblocked-of R1 R2))))))

(defrule team-done-with
  "The skill at X is over and its outcome digested: news of the machine,
   then the release (the team takes both in this order).  Also once the
   robot claims, waits for or works its next place (the outcome of the
   last skill is digested by then, not while GOTO-FINAL): holding the last
   place meanwhile makes teammates wait for a place nobody works."
  (declare (salience (+ ?*PRIORITY_CANDIDATE* 5)))
  ?w <- (team-want (resource ?x))
  (state IDLE|DONE|TEAM-CLAIM|TEAM-WAIT|EXEC)
  (not (intent (target ?x)))
  (not (skill-request (target ?x)))
  (not (output-at ?x ?))   ; a product left there to collect (collect.clp)
  (team-self (id ?me))
  =>
  (do-for-fact ((?m machine)) (eq ?m:name ?x)
    (loop-for-count ?*TEAM_NEWS_COPIES*
      (team-send-msg ?me news 0 ?x 0 0.0 ?m:mtype ?m:junk ?m:productions ?m:loaded-with)))
  (retract ?w))

(defrule team-news-machine
  "A teammate's belief of a machine it just worked: take it.  A robot still
   claiming a place decides again (its choice predates the news)."
  (declare (salience ?*PRIORITY_TEAM*))
  ?n <- (team-recv (taken TRUE) (kind news) (from ?f) (resource ?x)
          (data ?type ?junk ?made $?loaded))
  (team-self (id ?me&~?f))
  ?m <- (machine (name ?x))
  =>
  (retract ?n)
  (modify ?m (mtype ?type) (junk ?junk) (productions ?made) (loaded-with ?loaded))
  (do-for-fact ((?s state)) (eq (nth$ 1 ?s:implied) TEAM-CLAIM)
    (do-for-all-facts ((?i intent)) TRUE (retract ?i))
    (do-for-all-facts ((?w team-want))
        (not (or (any-factp ((?r skill-request)) (eq ?r:target ?w:resource))
                 (any-factp ((?o output-at)) (eq (nth$ 1 ?o:implied) ?w:resource))))
      (retract ?w))
    (retract ?s)
    (assert (state IDLE))))

;;; ---- the raw pucks: the team shares the storage's 20 -----------------------
;;; (Every robot plays to the end: recycling brings raw pucks back, and a team
;;; must not rely on any one robot being alive to finish the last products.)

(deftemplate team-s0-of
  "Raw pucks robot R has taken from the input storage (its news of INS)."
  (slot robot (type INTEGER))
  (slot taken (type INTEGER)))

(deffunction team-s0-taken ()
  "Raw pucks the team has taken, as far as this robot knows: its own and
   what the others' news of the input storage said."
  (bind ?n 0)
  (do-for-fact ((?c s0-taken)) TRUE (bind ?n (nth$ 1 ?c:implied)))
  (do-for-all-facts ((?o team-s0-of)) TRUE (bind ?n (+ ?n ?o:taken)))
  ?n)

(defrule team-news-storage
  "A teammate's count of the raw pucks it took."
  (declare (salience ?*PRIORITY_TEAM*))
  ?n <- (team-recv (taken TRUE) (kind news) (from ?f) (resource INS) (data ?k))
  (team-self (id ?me&~?f))
  =>
  (retract ?n)
  (do-for-all-facts ((?o team-s0-of)) (= ?o:robot ?f) (retract ?o))
  (assert (team-s0-of (robot ?f) (taken ?k))))

;;; A get-s0 that found no puck at the robot's spot (team seed 42: robot 3,
;;; stopped off its spot after a failed drive at the storage, believed it empty
;;; at 329 s and went without raw pucks for the rest of the game while the
;;; others took 8 more) is doubted while the team's count says raw pucks
;;; remain: after ?*TEAM_STORAGE_RECHECK_S* the storage is believed full again,
;;; at most ?*TEAM_STORAGE_DOUBTS* times a game (a count short of lost news, or
;;; of a dead robot's last pucks, costs no more than that many tries).

(defglobal
  ?*TEAM_STORAGE_RECHECK_S* = 20   ; s after an empty storage before it is doubted
  ?*TEAM_STORAGE_DOUBTS* = 2)      ; doubts per game

(deffacts team-storage-start
  (team-storage-doubts 0))

(defrule team-storage-empty-noted
  "The storage seemed empty: note when."
  (declare (salience ?*PRIORITY_TEAM_AGENT*))
  (input-storage empty)
  (team-clock (now ?t))
  (not (team-storage-empty-since ?))
  =>
  (assert (team-storage-empty-since ?t)))

(defrule team-storage-empty-doubted
  "The storage seemed empty a while ago, but fewer raw pucks than the supply
   were taken, as far as the team told: believe it full again (a robot done
   for want of pucks plays again)."
  (declare (salience ?*PRIORITY_TEAM_AGENT*))
  ?e <- (input-storage empty)
  ?f <- (team-storage-empty-since ?t0)
  (team-clock (now ?t&:(>= ?t (+ ?t0 ?*TEAM_STORAGE_RECHECK_S*))))
  ?d <- (team-storage-doubts ?k&:(< ?k ?*TEAM_STORAGE_DOUBTS*))
  (s0-supply ?n)
  (test (< (team-s0-taken) ?n))
  =>
  (retract ?e ?f ?d)
  (assert (team-storage-doubts (+ ?k 1)))
  (do-for-fact ((?s state)) (eq (nth$ 1 ?s:implied) DONE)
    (retract ?s)
    (assert (state IDLE))))

(defrule team-news-storage-send
  "Done at the input storage: tell the team how many raw pucks this robot took."
  (declare (salience (+ ?*PRIORITY_CANDIDATE* 6)))
  (state IDLE|DONE|TEAM-CLAIM|TEAM-WAIT|EXEC)
  (not (intent (target INS)))
  (not (skill-request (target INS)))
  (s0-taken ?k&:(> ?k 0))
  (team-self (id ?me))
  (not (team-s0-told ?k))
  =>
  (do-for-all-facts ((?t team-s0-told)) TRUE (retract ?t))
  (assert (team-s0-told ?k))
  (loop-for-count ?*TEAM_NEWS_COPIES* (team-send-msg ?me news 0 INS 0 0.0 ?k)))

(defrule team-done-junk-news
  "Done, hands empty, and a teammate's news tells of junk: recycling it scores
   and gives a raw puck, so the robot plays again."
  (declare (salience ?*PRIORITY_TEAM_AGENT*))
  ?s <- (state DONE)
  (holding NONE)
  (not (no-recycling))
  (exists (machine (junk ?j&:(> ?j 0))))
  =>
  (retract ?s)
  (assert (state IDLE)))

;;; ---- a robot that waits long takes other work -----------------------------
;;; Waiting for a place another robot works costs the whole team time: after
;;; ?*TEAM_WAIT_OTHER_WORK_S* of waits the robot takes the best use of its puck
;;; at a place nobody holds, even of lower priority than the busy one, or,
;;; hands empty, junk or a raw puck elsewhere (the paper's priorities decide
;;; among the free places; a free place is claimed as any other).

(defglobal ?*TEAM_WAIT_OTHER_WORK_S* = 20)   ; s: waits before other work

(deffunction team-s1-awaited ()
  "TRUE if some machine waits for an S1 a T1 could make (as production.clp's
   awaits-s1: a T2 or T2_3 holding just an S0, or a started T3 without S1)."
  (any-factp ((?m machine))
    (and (not (member$ S1 ?m:loaded-with))
         (or (and (member$ ?m:mtype (create$ T2 T2_3))
                  (= (length$ ?m:loaded-with) 1) (member$ S0 ?m:loaded-with))
             (and (eq ?m:mtype T3) (> (length$ ?m:loaded-with) 0))))))

(deffunction team-puck-use
  "The machine priority (utils.clp PRIO_*) of bringing puck ?x to a machine
   believed ?mt loaded with ?lw, as the candidate rules of production.clp
   rank it; 0 if no candidate rule would pick it."
  (?x ?mt $?lw)
  (bind ?n (length$ ?lw))
  (bind ?new (not (member$ ?x ?lw)))
  (bind ?any (member$ ?x (create$ S0 S1 S2)))
  (bind ?low (member$ ?x (create$ S0 S1)))
  (if (and ?any ?new (eq ?mt T3) (= ?n 2)) then (return ?*PRIO_COMPLETE_P*))
  (if (and ?low ?new (eq ?mt T2) (= ?n 1)) then (return ?*PRIO_COMPLETE_S2*))
  (if (and (eq ?mt T2_3) (= ?n 1)
           (or (and (eq ?x S0) (eq (nth$ 1 ?lw) S1))
               (and (eq ?x S1) (eq (nth$ 1 ?lw) S0))))
   then (return ?*PRIO_RESOLVE_T23*))
  (if (and ?any ?new (eq ?mt T3) (= ?n 1)) then (return ?*PRIO_T3_PROGRESS*))
  (if (and (eq ?x S0) (eq ?mt T1) (team-s1-awaited)) then (return ?*PRIO_FEED_S1*))
  (if (and ?low (eq ?mt T2) (= ?n 0)) then (return ?*PRIO_T2_START*))
  (if (and (eq ?x S2) (eq ?mt T3) (= ?n 0)) then (return ?*PRIO_T3_START_S2*))
  (if (and ?low (eq ?mt T3) (= ?n 0)) then (return ?*PRIO_T3_START*))
  (if (and (eq ?x S0) (eq ?mt T1)) then (return ?*PRIO_T1*))
  (if (and (eq ?x S2) (eq ?mt T2_3) ?new) then (return ?*PRIO_EXPLORE_T23*))
  (if (and ?any (eq ?mt T1_2_3) (= ?n 0)) then (return ?*PRIO_EXPLORE*))
  (if (and ?low (eq ?mt T1_2) (= ?n 0)) then (return ?*PRIO_EXPLORE*))
  0)

(deffunction team-free-use-of
  "The free machine where puck ?x is of most use (nearest to ?here among
   equals), or nil if no free machine takes it."
  (?x ?here)
  (bind ?free (team-free-of M1 M2 M3 M4 M5 M6 M7 M8 M9 M10))
  (bind ?best nil)
  (bind ?best-p 0)
  (bind ?best-d 0.0)
  (do-for-all-facts ((?m machine)) (member$ ?m:name ?free)
    (bind ?p (team-puck-use ?x ?m:mtype ?m:loaded-with))
    (bind ?d (place-distance ?here ?m:name))
    (if (and (> ?p 0)
             (or (> ?p ?best-p) (and (= ?p ?best-p) (< ?d ?best-d))))
     then (bind ?best ?m:name) (bind ?best-p ?p) (bind ?best-d ?d)))
  ?best)

(deffunction team-stop-waiting ()
  "Drop what the robot claims or waits for now (the release goes out)."
  (do-for-all-facts ((?w team-waiting)) TRUE (retract ?w))
  (do-for-all-facts ((?i intent)) TRUE
    (do-for-all-facts ((?w team-want))
        (and (eq ?w:resource ?i:target)
             (not (any-factp ((?o output-at)) (eq (nth$ 1 ?o:implied) ?w:resource))))
      (retract ?w))
    (retract ?i)))

(defrule team-wait-other-machine
  "Waited or claimed long with a puck: bring it to the free machine where it
   is of most use (before team-wait-breaks-hold-cycle, which would throw it
   away).  The wait counts anew from here, so the robot does not switch
   places again at once."
  (declare (salience (+ ?*PRIORITY_TEAM_AGENT* 1)))
  ?s <- (state TEAM-CLAIM|TEAM-WAIT)
  ?b <- (team-wait-since ?t0)
  (team-clock (now ?t&:(>= ?t (+ ?t0 ?*TEAM_WAIT_OTHER_WORK_S*))))
  (holding ?p&S0|S1|S2)
  (robot-at ?here)
  (test (neq (team-free-use-of ?p ?here) nil))
  =>
  (bind ?y (team-free-use-of ?p ?here))
  (retract ?b)
  (assert (team-wait-since ?t))
  ;; The test above was evaluated when its facts last changed: a vote heard since may
  ;; have taken the place (then ?y is nil and the robot waits on).
  (if (and (neq ?y nil) (not (any-factp ((?i intent)) (eq ?i:target ?y))))
   then (retract ?s)
        (team-stop-waiting)
        (assert (state IDLE) (intent (action finish-puck-at) (target ?y)))))

(deffunction team-free-empty-handed-work
  "Hands empty: the nearest free machine with junk, else the input storage
   if it is free and has raw pucks; nil if neither."
  (?here)
  (bind ?junk (create$))
  (do-for-all-facts ((?m machine)) (> ?m:junk 0) (bind ?junk (create$ ?junk ?m:name)))
  (bind ?free (team-free-of ?junk))
  (if (> (length$ ?free) 0) then (return (team-nearest-of ?here ?free)))
  (if (and (not (any-factp ((?e input-storage)) TRUE))
           (> (length$ (team-free-of INS)) 0))
   then (return INS))
  nil)

(defrule team-wait-other-work-empty-handed
  "Waited or claimed long with empty hands (for a machine's junk or the
   storage): junk at a free machine, else a raw puck from the free storage."
  (declare (salience (+ ?*PRIORITY_TEAM_AGENT* 1)))
  ?s <- (state TEAM-CLAIM|TEAM-WAIT)
  ?b <- (team-wait-since ?t0)
  (team-clock (now ?t&:(>= ?t (+ ?t0 ?*TEAM_WAIT_OTHER_WORK_S*))))
  (holding NONE)
  (robot-at ?here)
  (test (neq (team-free-empty-handed-work ?here) nil))
  =>
  (bind ?y (team-free-empty-handed-work ?here))
  (retract ?b)
  (assert (team-wait-since ?t))
  (bind ?a get-junk)
  (if (eq ?y INS) then (bind ?a get-s0))
  ;; As above: nil once a vote heard since took the place (seed 9 on a lossy link: the
  ;; storage, free when the test ran, was a teammate's when the rule fired, and the
  ;; intent (get-junk nil) stopped robot 2's agent for the whole game).
  (if (and (neq ?y nil) (not (any-factp ((?i intent)) (eq ?i:target ?y))))
   then (retract ?s)
        (team-stop-waiting)
        (assert (state IDLE) (intent (action ?a) (target ?y)))))

;;; ---- a place the robot cannot drive to ----------------------------------
;;; A killed robot's body stays where its wheels stopped, on a machine's
;;; approach too: the others drove there, failed and chose it again for the
;;; rest of the game (kill-one seed 18: robots 1 and 2 failed 40 drives to M2,
;;; 101 points, one robot alone 144).  The executor tells which failures were
;;; drives that could not get there, or to a machine stopped on the bumper after
;;; 2 s of driving (team-unreached, asserted with the outcome); after ?*TEAM_UNREACHED_TRIES* in a row at one place the robot
;;; avoids it for ?*TEAM_BLOCKED_S* and takes other work at once.

(defglobal
  ?*TEAM_UNREACHED_TRIES* = 2   ; failed drives in a row to one place
  ?*TEAM_BLOCKED_S* = 120.0)    ; s a place is then avoided

(deftemplate team-unreached
  "From the executor: skill id failed because the robot could not drive to
   its place, or its bumper stopped it on the way to a machine."
  (slot id (type INTEGER)))

(deftemplate team-unreached-count
  "Failed drives in a row to a place (since a skill there last ended FINAL)."
  (slot resource (type SYMBOL))
  (slot count (type INTEGER)))

(defrule team-unreached-place
  "A drive to X failed: count it (before execution digests the outcome);
   at ?*TEAM_UNREACHED_TRIES* X is blocked for a while."
  (declare (salience (+ ?*PRIORITY_TEAM_AGENT* 2)))
  ?u <- (team-unreached (id ?id))
  (skill-request (id ?id) (target ?x))
  (skill-outcome (id ?id) (status FAILED))
  (team-clock (now ?t))
  =>
  (retract ?u)
  (bind ?n 1)
  (do-for-all-facts ((?c team-unreached-count)) (eq ?c:resource ?x)
    (bind ?n (+ ?c:count 1))
    (retract ?c))
  (if (>= ?n ?*TEAM_UNREACHED_TRIES*)
   then (do-for-all-facts ((?b team-blocked)) (eq ?b:resource ?x) (retract ?b))
        (printout t "WARN " ?x " not reached " ?n " times: avoided until "
                  (+ ?t ?*TEAM_BLOCKED_S*) crlf)
        (assert (team-blocked (resource ?x) (until (+ ?t ?*TEAM_BLOCKED_S*))))
   else (assert (team-unreached-count (resource ?x) (count ?n)))))

(defrule team-unreached-stale
  "A team-unreached whose skill is gone (nothing to count)."
  (declare (salience (+ ?*PRIORITY_TEAM_AGENT* 2)))
  ?u <- (team-unreached (id ?id))
  (not (skill-request (id ?id)))
  =>
  (retract ?u))

(defrule team-reached-place
  "A skill at X ended FINAL: the next failed drive there counts from one."
  (declare (salience (+ ?*PRIORITY_TEAM_AGENT* 2)))
  (skill-request (id ?id) (target ?x))
  (skill-outcome (id ?id) (status FINAL))
  ?c <- (team-unreached-count (resource ?x))
  =>
  (retract ?c))

(defrule team-intent-blocked-other-unit
  "Recycling or a discard at a unit blocked for this robot: the other unit,
   if it is not blocked too (before team-intent-blocked: a robot waiting with
   its hands full for a unit it cannot reach has no other work; waiting to
   discard there, it was sent to discard there again, a rule loop that
   stopped its agent on kill-one seeds 92 and 97)."
  (declare (salience (+ ?*PRIORITY_TEAM_AGENT* 2)))
  (state IDLE)
  ?i <- (intent (action recycle|discard) (target ?x&R1|R2))
  (team-clock (now ?t))
  (team-blocked (resource ?x) (until ?b&:(> ?b ?t)))
  (test (> (length$ (team-unblocked-of R1 R2)) 0))
  =>
  (bind ?y (nth$ 1 (team-unblocked-of R1 R2)))
  (do-for-all-facts ((?w team-want))
      (and (eq ?w:resource ?x)
           (not (any-factp ((?o output-at)) (eq (nth$ 1 ?o:implied) ?x))))
    (retract ?w))
  (modify ?i (target ?y)))

(defrule team-intent-blocked
  "An intent at a place blocked for this robot: drop it and wait for the
   place as for a held one, the wait counted long enough for other work at
   once (the rules of 'a robot that waits long' below)."
  (declare (salience (+ ?*PRIORITY_TEAM_AGENT* 1)))
  ?s <- (state IDLE)
  ?i <- (intent (target ?x))
  (team-clock (now ?t))
  (team-blocked (resource ?x) (until ?b&:(> ?b ?t)))
  =>
  (retract ?s ?i)
  (do-for-all-facts ((?w team-want))
      (and (eq ?w:resource ?x)
           (not (any-factp ((?o output-at)) (eq (nth$ 1 ?o:implied) ?x))))
    (retract ?w))
  (do-for-all-facts ((?w team-wait-since)) TRUE (retract ?w))
  (assert (state TEAM-WAIT) (team-waiting ?x)
          (team-wait-since (- ?t ?*TEAM_WAIT_OTHER_WORK_S*))))

;;; The block is a guess (a teammate met in a lane can push a robot onto a
;;; machine's corner twice in a row: team seed 32's robot 1 then held an S2
;;; that only the blocked M10 and a T3 a teammate worked could take, and stood
;;; still 61 s).  A robot that finds no other work tries the blocked place
;;; again after ?*TEAM_BLOCKED_RETRY_S* rather than stand still: a failure
;;; there costs one drive, standing costs the game's time.

(defglobal ?*TEAM_BLOCKED_RETRY_S* = 20)   ; s of waiting without other work

(defrule team-blocked-retry
  "Waiting for a place blocked for this robot, which no teammate holds, with
   no other work found meanwhile (the wait rules below would have taken it):
   after ?*TEAM_BLOCKED_RETRY_S* the block ends and the robot decides anew."
  (declare (salience ?*PRIORITY_TEAM_AGENT*))
  ?s <- (state TEAM-WAIT)
  ?w <- (team-waiting ?x)
  (team-wait-since ?t0)
  (team-clock (now ?t&:(>= ?t (+ ?t0 ?*TEAM_WAIT_OTHER_WORK_S* ?*TEAM_BLOCKED_RETRY_S*))))
  ?b <- (team-blocked (resource ?x) (until ?u&:(> ?u ?t)))
  (team-self (id ?me))
  (not (team-vote (resource ?x) (holder ~?me) (until ?v&:(> ?v ?t))))
  =>
  (retract ?s ?w ?b)
  (printout t "WARN no other work for " (- ?t ?t0 ?*TEAM_WAIT_OTHER_WORK_S*)
            " s: " ?x " tried again" crlf)
  (assert (state IDLE)))

;;; A robot can wait with a puck in hand that no free place takes for a long
;;; time: the T3 it would advance works for 50 s and its robot holds it until
;;; it collects the product, and the other robots' pucks fill the free places
;;; (team seed 91: robot 3 held an S1 for M6 61 s; seed 72: 61 s with its own
;;; product out, the other-work rule trying a place every 20 s and so never
;;; letting the hold-cycle rule's 20 s pass).  After ?*TEAM_WAIT_PUCK_MAX_S* of
;;; waits in all since its last skill (team-idle-since: not restarted by the
;;; other-work rules) the robot lets go of the puck and takes empty-handed
;;; work: a raw or half-made puck is worth less than the time.

(defglobal ?*TEAM_WAIT_PUCK_MAX_S* = 40)   ; s of waits with a puck, then discard

(defrule team-wait-lets-go-of-puck
  "Waited or claimed ?*TEAM_WAIT_PUCK_MAX_S* since the last skill with a
   raw or half-made puck and still no free place takes it: drop the claim
   or the wait and discard the puck at a recycling unit this robot can
   reach (the other-work rules, of higher salience, take a free place
   first; on a lossy link a claim can stay pending that long)."
  (declare (salience ?*PRIORITY_TEAM_AGENT*))
  ?s <- (state TEAM-CLAIM|TEAM-WAIT)
  (team-idle-since ?t0)
  (team-clock (now ?t&:(>= ?t (+ ?t0 ?*TEAM_WAIT_PUCK_MAX_S*))))
  (holding ?p&S0|S1|S2)
  (robot-at ?here)
  (test (> (length$ (team-unblocked-of R1 R2)) 0))
  =>
  (retract ?s)
  (team-stop-waiting)
  (do-for-all-facts ((?b team-wait-since)) TRUE (retract ?b))
  (printout t "WARN waited " (- ?t ?t0) " s with " ?p ": discard" crlf)
  (assert (state IDLE)
          (intent (action discard)
                  (target (nearest-of ?here (team-unblocked-of R1 R2))))))
