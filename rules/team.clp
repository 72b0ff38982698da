;;; team.clp -- the team's claims on shared resources, one engine per robot.
;;;
;;; A machine (M1..M10), a delivery gate (D1..D3) and a recycling unit (R1, R2)
;;; are resources (team-agent.clp; the input storage is not: each robot has
;;; its own spot there).  A robot that wants one asserts (team-want (resource X)); it
;;; holds X while it has a (team-claim (resource X) (until U)) with U later than
;;; its own (team-clock (now)).  Claims are leases granted by a majority of the
;;; team: every robot is a voter that gives its vote for X to one robot at a
;;; time, for the lease the request carries, counted on the voter's own clock
;;; from when the request arrived; the claimant counts its lease from when it
;;; SENT the request, so its hold ends before any vote it counted can.  Two
;;; majorities share a voter, so two robots never hold X at once, whatever the
;;; network loses, delays, duplicates or reorders; clocks need the same rate,
;;; not the same reading.  A dead robot's claims end when its leases do.
;;; The protocol, its messages and its argument: rules/README.md, "Team".
;;;
;;; Host interface: assert (team-self (id I) (robots N)) and (team-clock (now
;;; T)) once, then move the clock with (team-set-time T); take every
;;; (team-send) fact out (retract it) and give it to the other robots as a
;;; (team-recv) with the same slots plus (from I).  The robot's own messages
;;; come back to it through rules here, never through the host.

(defglobal
  ?*TEAM_LEASE* = 20.0       ; seconds of game time a vote lasts
  ?*TEAM_RENEW* = 2.0        ; a holding claimant asks again this often
  ?*TEAM_ROUND* = 10.0       ; a round without a majority ends after this
  ?*TEAM_RENEW_RETRY* = 5.0  ; ... a renewal round of a held claim already after this
  ?*TEAM_MARGIN* = 0.5       ; clock rate differences over one lease
  ?*TEAM_SEQ* = 1            ; number of this robot's next message (reset starts at 1)
  ?*PRIORITY_TEAM_DROP* = 460   ; duplicates and late messages go first
  ?*PRIORITY_TEAM* = 450)       ; then messages in sender order

(deftemplate team-self
  "Who this robot is and how many robots the team has (majority = more than half)."
  (slot id (type INTEGER))
  (slot robots (type INTEGER) (default 1)))

(deftemplate team-clock
  "This robot's game time; robots need not agree on it."
  (slot now (type NUMBER) (default 0.0)))

(deftemplate team-want
  "The agent wants resource X; retracting it releases the claim."
  (slot resource (type SYMBOL)))

(deftemplate team-claim
  "This robot's claim on X: the current round (= sequence number of its
   request), when the round's request was sent, the voters that granted that
   round, and until when the claim is held (negative: never held)."
  (slot resource (type SYMBOL))
  (slot round (type INTEGER))
  (slot sent (type NUMBER))
  (multislot votes (type INTEGER))
  (slot done (type SYMBOL) (allowed-symbols TRUE FALSE) (default FALSE)) ; majority reached
  (slot until (type NUMBER) (default -1.0)))

(deftemplate team-backoff
  "A claim round failed: ask for X again only after this time (robot id
   staggers the retries, so robots that split the votes do not collide again)."
  (slot resource (type SYMBOL))
  (slot until (type NUMBER)))

(deftemplate team-vote
  "This robot's vote on X: given to holder until that time (own clock)."
  (slot resource (type SYMBOL))
  (slot holder (type INTEGER))
  (slot until (type NUMBER)))

(deftemplate team-peer
  "The highest number of a request or release about resource X taken from
   robot id (self included)."
  (slot id (type INTEGER))
  (slot resource (type SYMBOL))
  (slot seen (type INTEGER) (default 0)))

(deftemplate team-news-seen
  "The highest news number about X taken from robot id: news has an order of
   its own, so a release or request that overtakes it does not drop it."
  (slot id (type INTEGER))
  (slot resource (type SYMBOL))
  (slot seen (type INTEGER)))

(deftemplate team-send
  "A message for the host to broadcast.  request: rseq = seq, lease asked;
   grant: to the claimant, rseq = the request's seq, lease granted; deny:
   to the claimant, rseq = the request's seq, the vote is another's;
   release: the sender gives X up; news: what the sender believes of X
   (data), for the agent's rules (team-agent.clp)."
  (slot seq (type INTEGER))
  (slot kind (type SYMBOL) (allowed-symbols request grant deny release news))
  (slot to (type INTEGER) (default 0))          ; 0: everybody
  (slot resource (type SYMBOL))
  (slot rseq (type INTEGER) (default 0))
  (slot lease (type NUMBER) (default 0.0))
  (multislot data))                             ; news: what the sender believes of X

(deftemplate team-recv
  "A message from robot from (the host's copy of its team-send)."
  (slot from (type INTEGER))
  (slot seq (type INTEGER))
  (slot kind (type SYMBOL) (allowed-symbols request grant deny release news))
  (slot to (type INTEGER) (default 0))
  (slot resource (type SYMBOL))
  (slot rseq (type INTEGER) (default 0))
  (slot lease (type NUMBER) (default 0.0))
  (multislot data)
  (slot taken (type SYMBOL) (allowed-symbols TRUE FALSE) (default FALSE)))

(deffunction team-set-time (?t)
  "The host moves this robot's clock."
  (do-for-fact ((?c team-clock)) TRUE (modify ?c (now ?t)))
  ?t)

(deffunction team-majority (?votes ?robots)
  (> (* 2 ?votes) ?robots))

(deffunction team-send-msg (?me ?kind ?to ?x ?rseq ?lease $?data)
  "Numbers a message, hands it to the host and delivers it to this robot
   itself (a robot votes on its own requests like everybody else's)."
  (bind ?seq ?*TEAM_SEQ*)
  (bind ?*TEAM_SEQ* (+ ?seq 1))
  (if (= ?rseq 0) then (bind ?rseq ?seq))
  (assert (team-send (seq ?seq) (kind ?kind) (to ?to) (resource ?x)
                     (rseq ?rseq) (lease ?lease) (data ?data)))
  (assert (team-recv (from ?me) (seq ?seq) (kind ?kind) (to ?to) (resource ?x)
                     (rseq ?rseq) (lease ?lease) (data ?data)))
  ?seq)

;;; ---------------------------------------------------------------- messages

(defrule team-peer-new
  "The first request or release from robot f about X."
  (declare (salience (+ ?*PRIORITY_TEAM_DROP* 1)))
  (team-recv (from ?f) (kind request|release) (resource ?x) (taken FALSE))
  (not (team-peer (id ?f) (resource ?x)))
  =>
  (assert (team-peer (id ?f) (resource ?x))))

(defrule team-drop-old
  "A message not newer than the last taken from its sender about the same
   resource is a duplicate or was overtaken: dropping it is the same as
   losing it."
  (declare (salience ?*PRIORITY_TEAM_DROP*))
  ?m <- (team-recv (from ?f) (kind request|release) (resource ?x) (seq ?s) (taken FALSE))
  (team-peer (id ?f) (resource ?x) (seen ?n&:(<= ?s ?n)))
  =>
  (retract ?m))

(defrule team-drop-old-news
  "News not newer than the last news about X taken from its sender: a copy,
   or overtaken by newer news (which says more)."
  (declare (salience ?*PRIORITY_TEAM_DROP*))
  ?m <- (team-recv (from ?f) (kind news) (resource ?x) (seq ?s) (taken FALSE))
  (team-news-seen (id ?f) (resource ?x) (seen ?n&:(<= ?s ?n)))
  =>
  (retract ?m))

(defrule team-take-news
  "News is taken as it comes, newest per sender and resource; it only informs
   the agent's beliefs, so its order against claims does not matter."
  (declare (salience ?*PRIORITY_TEAM*))
  ?m <- (team-recv (from ?f) (kind news) (resource ?x) (seq ?s) (taken FALSE))
  (not (team-news-seen (id ?f) (resource ?x) (seen ?n&:(>= ?n ?s))))
  =>
  (do-for-all-facts ((?o team-news-seen)) (and (= ?o:id ?f) (eq ?o:resource ?x))
    (retract ?o))
  (assert (team-news-seen (id ?f) (resource ?x) (seen ?s)))
  (modify ?m (taken TRUE)))

(defrule team-take
  "Take each sender's requests and releases about X in its order: the oldest
   pending one first."
  (declare (salience ?*PRIORITY_TEAM*))
  ?m <- (team-recv (from ?f) (kind request|release) (resource ?x) (seq ?s) (taken FALSE))
  ?p <- (team-peer (id ?f) (resource ?x) (seen ?n&:(> ?s ?n)))
  (not (team-recv (from ?f) (kind request|release) (resource ?x) (seq ?o&:(< ?o ?s)) (taken FALSE)))
  =>
  (modify ?p (seen ?s))
  (modify ?m (taken TRUE)))

(defrule team-take-reply
  "A grant or denial answers one round of one claimant, named by its number
   (rseq): the round, not the voter's order, decides whether it counts, so it
   is taken as it comes.  In the voters' order, a robot's grant of its own
   request (sent right after it) that overtook the request on a link with
   random delays dropped the request as old: half the renewals were lost,
   and holds lapsed under skills (seed 39 with 10 % loss and 2 s delays)."
  (declare (salience ?*PRIORITY_TEAM*))
  ?m <- (team-recv (kind grant|deny) (taken FALSE))
  =>
  (modify ?m (taken TRUE)))

;;; ---------------------------------------------------------------- voter

(defrule team-vote-grant
  "A request for X: grant it unless the vote is given to another robot and
   has not run out.  The vote lasts the asked lease on this robot's clock."
  (declare (salience ?*PRIORITY_TEAM*))
  ?m <- (team-recv (taken TRUE) (kind request) (from ?r) (resource ?x) (seq ?s) (lease ?l))
  (team-self (id ?me))
  (team-clock (now ?t))
  (not (team-vote (resource ?x) (holder ~?r) (until ?u&:(> ?u ?t))))
  =>
  (retract ?m)
  (do-for-all-facts ((?v team-vote)) (eq ?v:resource ?x) (retract ?v))
  (assert (team-vote (resource ?x) (holder ?r) (until (+ ?t ?l))))
  (team-send-msg ?me grant ?r ?x ?s ?l))

(defrule team-vote-refuse
  "The vote on X is another robot's: say so (the claimant backs off)."
  (declare (salience ?*PRIORITY_TEAM*))
  ?m <- (team-recv (taken TRUE) (kind request) (from ?r) (resource ?x) (seq ?s))
  (team-self (id ?me))
  (team-clock (now ?t))
  (team-vote (resource ?x) (holder ~?r) (until ?u&:(> ?u ?t)))
  =>
  (retract ?m)
  (team-send-msg ?me deny ?r ?x ?s 0.0))

(defrule team-vote-release
  "The holder gave X up: the vote is free at once."
  (declare (salience ?*PRIORITY_TEAM*))
  ?m <- (team-recv (taken TRUE) (kind release) (from ?r) (resource ?x))
  =>
  (retract ?m)
  (do-for-all-facts ((?v team-vote)) (and (eq ?v:resource ?x) (= ?v:holder ?r))
    (retract ?v)))

;;; ---------------------------------------------------------------- claimant

(defrule team-grant-counted
  "A vote for the current round; a majority holds X until the round's send
   time plus the lease (minus the margin for clock rates)."
  (declare (salience ?*PRIORITY_TEAM*))
  ?m <- (team-recv (taken TRUE) (kind grant) (from ?v) (to ?me) (resource ?x) (rseq ?r) (lease ?l))
  (team-self (id ?me) (robots ?n))
  ?c <- (team-claim (resource ?x) (round ?r) (sent ?sent) (votes $?vs) (until ?u))
  =>
  (retract ?m)
  (if (not (member$ ?v ?vs))
   then (bind ?vs (create$ ?vs ?v))
        (if (team-majority (length$ ?vs) ?n)
         then (modify ?c (votes ?vs) (done TRUE)
                         (until (max ?u (- (+ ?sent ?l) ?*TEAM_MARGIN*))))
         else (modify ?c (votes ?vs)))))

(defrule team-denied
  "A voter's vote is another robot's and the claim is not held: give up now
   (release the votes this round got) and ask again after the back-off."
  (declare (salience ?*PRIORITY_TEAM*))
  ?m <- (team-recv (taken TRUE) (kind deny) (to ?me) (resource ?x) (rseq ?r))
  (team-self (id ?me))
  ?c <- (team-claim (resource ?x) (round ?r) (until ?u))
  (team-clock (now ?t&:(>= ?t ?u)))
  =>
  (retract ?m ?c)
  (team-send-msg ?me release 0 ?x 0 0.0)
  (assert (team-backoff (resource ?x) (until (+ ?t (* ?me (/ ?*TEAM_RENEW* 2)))))))

(defrule team-news-unread
  "News nobody's rules read (a team without team-agent.clp)."
  (declare (salience (- ?*PRIORITY_TEAM* 1)))
  ?m <- (team-recv (taken TRUE) (kind news))
  =>
  (retract ?m))

(defrule team-grant-stale
  "A grant or denial for another robot, or for a round that is over, or a
   denial of a claim that is held (it renews on the other votes)."
  (declare (salience (- ?*PRIORITY_TEAM* 1)))
  ?m <- (team-recv (taken TRUE) (kind grant|deny))
  =>
  (retract ?m))

(defrule team-ask
  "The agent wants X: send a request (round 1 of the claim)."
  (declare (salience ?*PRIORITY_TEAM*))
  (team-want (resource ?x))
  (not (team-claim (resource ?x)))
  (team-self (id ?me))
  (team-clock (now ?t))
  (not (team-backoff (resource ?x) (until ?b&:(> ?b ?t))))
  =>
  (do-for-all-facts ((?o team-backoff)) (eq ?o:resource ?x) (retract ?o))
  (bind ?seq (team-send-msg ?me request 0 ?x 0 ?*TEAM_LEASE*))
  (assert (team-claim (resource ?x) (round ?seq) (sent ?t))))

(defrule team-renew
  "Held: a new round once the last one got its majority and is a renewal
   interval old, or got none within the retry time (lost messages: several
   tries fit in one lease, so a hold lapses only when all of them fail); the
   hold extends when a round gets its own majority."
  (declare (salience ?*PRIORITY_TEAM*))
  (team-want (resource ?x))
  ?c <- (team-claim (resource ?x) (sent ?sent) (done ?done) (until ?u))
  (team-self (id ?me))
  (team-clock (now ?t&:(< ?t ?u)
                    &:(or (and (eq ?done TRUE) (>= ?t (+ ?sent ?*TEAM_RENEW*)))
                          (>= ?t (+ ?sent ?*TEAM_RENEW_RETRY*)))))
  =>
  (bind ?seq (team-send-msg ?me request 0 ?x 0 ?*TEAM_LEASE*))
  (modify ?c (round ?seq) (sent ?t) (votes) (done FALSE)))

(defrule team-give-up
  "Not held and the round ran out of time (votes split or lost): release
   what votes the round got and ask again after a back-off that grows with
   the robot id."
  (declare (salience ?*PRIORITY_TEAM*))
  ?c <- (team-claim (resource ?x) (sent ?sent) (until ?u))
  (team-self (id ?me))
  (team-clock (now ?t&:(>= ?t ?u)&:(>= ?t (+ ?sent ?*TEAM_ROUND*))))
  =>
  (retract ?c)
  (team-send-msg ?me release 0 ?x 0 0.0)
  (assert (team-backoff (resource ?x) (until (+ ?t (* ?me (/ ?*TEAM_RENEW* 2)))))))

(defrule team-release
  "The agent no longer wants X: tell the voters, so X is free before the lease ends."
  (declare (salience ?*PRIORITY_TEAM*))
  ?c <- (team-claim (resource ?x))
  (not (team-want (resource ?x)))
  (team-self (id ?me))
  =>
  (retract ?c)
  (team-send-msg ?me release 0 ?x 0 0.0))

(deffunction team-holds (?x)
  "TRUE when this robot holds resource ?x now."
  (bind ?now -1.0)
  (do-for-fact ((?c team-clock)) TRUE (bind ?now ?c:now))
  (any-factp ((?k team-claim)) (and (eq ?k:resource ?x) (> ?k:until ?now))))
