;;; strategy: paper
;;; Execution monitoring: skill outcomes, failures, back to IDLE.

;; Idle with empty hands: the first decision fetches a raw puck.
(reset)
(run)
(t-expect-request "exec idle empty hands: get-s0 at INS" get-s0 INS)
(t-expect-state "exec request: state EXEC" EXEC)

;; get-s0 FINAL: holding S0, and the next decision explores M1.
(reset)
(t-outcome get-s0 INS FINAL none)
(run)
(t-expect-holding "exec get-s0 final: holding S0" S0)
(t-expect-request "exec get-s0 final: next explores M1" finish-puck-at M1)

;; finish-puck-at FAILED (puck lost): abort, hands empty, fetch again.
(reset)
(t-holding S1)
(t-machine M2 T2 S0)
(t-outcome finish-puck-at M2 FAILED none)
(run)
(t-expect-holding "exec failed: holding nothing" NONE)
(t-expect-machine "exec failed: machine belief kept" M2 T2 S0)
(t-expect-request "exec failed: idle again, fetches" get-s0 INS)

;; Delivery done: hands empty, fetch again.
(reset)
(assert (active-gate D3))
(t-holding P)
(t-outcome deliver D3 FINAL none)
(run)
(t-expect-holding "exec delivered: hands empty" NONE)
(t-expect-request "exec delivered: fetches" get-s0 INS)

;; The storage is empty: nothing left to do.
(reset)
(assert (skill-request (id 1) (name get-s0) (target INS))
        (skill-outcome (id 1) (status FAILED) (info storage-empty)))
(do-for-all-facts ((?s state)) TRUE (retract ?s))
(assert (state EXEC))
(run)
(t-expect-state "exec storage empty: DONE" DONE)
(t-expect-no-request "exec storage empty: no more requests")

;; Recycling: known junk comes before the input storage, nearest first.
(reset)
(t-at M1)
(do-for-fact ((?m machine)) (eq ?m:name M8) (modify ?m (mtype T3) (junk 2)))
(do-for-fact ((?m machine)) (eq ?m:name M4) (modify ?m (mtype T2) (junk 1)))
(run)
(t-expect-request "exec junk known: fetch the nearest junk" get-junk M4)

;; Junk taken: holding JUNK, one less there, off to the nearest unit.
(reset)
(do-for-fact ((?m machine)) (eq ?m:name M2) (modify ?m (mtype T2) (junk 1)))
(t-outcome get-junk M2 FINAL none)
(run)
(t-expect-holding "exec junk taken: holding JUNK" JUNK)
(t-expect-junk "exec junk taken: none left at M2" M2 0 0)
(t-expect-request "exec junk taken: to the nearest recycling unit" recycle R1)

;; No junk where believed: believe none, fetch a raw puck instead.
(reset)
(do-for-fact ((?m machine)) (eq ?m:name M9) (modify ?m (mtype T3) (junk 2)))
(t-outcome get-junk M9 FAILED none)
(do-for-all-facts ((?o skill-outcome)) TRUE (modify ?o (info no-junk)))
(run)
(t-expect-junk "exec no junk: believe none" M9 0 0)
(t-expect-request "exec no junk: fetch a raw puck" get-s0 INS)

;; Recycled: the unit hands back an S0, which goes to production.
(reset)
(t-holding JUNK)
(t-outcome recycle R2 FINAL none)
(run)
(t-expect-holding "exec recycled: holding S0" S0)
(t-expect-request "exec recycled: the S0 explores M1" finish-puck-at M1)

;; Storage empty but junk known: not done, recycle it.
(reset)
(assert (input-storage empty))
(do-for-fact ((?m machine)) (eq ?m:name M5) (modify ?m (mtype T2) (junk 1)))
(run)
(t-expect-request "exec storage empty, junk known: fetch junk" get-junk M5)

;; A failed transport with the puck still in the gripper: keep it, try again.
(reset)
(t-holding S1)
(t-machine M2 T2 S0)
(t-outcome-sensed finish-puck-at M2 FAILED none puck-held)
(run)
(t-expect-holding "exec failed, puck held: still holding S1" S1)
(t-expect-machine "exec failed, puck held: machine belief kept" M2 T2 S0)
(t-expect-request "exec failed, puck held: the S1 goes to M2 again" finish-puck-at M2)

;; A failed delivery with the P still held: deliver it again.
(reset)
(assert (active-gate D2))
(t-holding P)
(t-outcome-sensed deliver D2 FAILED none puck-held)
(run)
(t-expect-holding "exec failed delivery, puck held: still holding P" P)
(t-expect-request "exec failed delivery, puck held: deliver again" deliver D2)

;; Kept failures in a row: after KEPT_TRIES the puck is believed lost.
(reset)
(t-holding S1)
(t-machine M2 T2 S0)
(do-for-all-facts ((?k kept-failures)) TRUE (retract ?k))
(assert (kept-failures 2))
(t-outcome-sensed finish-puck-at M2 FAILED none puck-held)
(run)
(t-expect-holding "exec third kept failure: believed lost" NONE)
(t-expect-request "exec third kept failure: fetch anew" get-s0 INS)
