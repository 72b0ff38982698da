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
