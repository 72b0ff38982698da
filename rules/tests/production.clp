;;; strategy: paper
;;; Production (the paper's priorities, ties by machine name): given the
;;; beliefs and the held puck, the next committed action.

;; Paper, Figure 3: holding S0, a T1 known and a T2_3 loaded with S1:
;; the S0 goes to the T2_3.
(reset)
(t-holding S0)
(t-machine M1 T1)
(t-machine M3 T2_3 S1)
(run)
(t-expect-request "prod paper example: S0 to the T2_3+S1" finish-puck-at M3)

;; Paper text: holding S0, a T1 and a T2 loaded with S1: prefer the T2.
(reset)
(t-holding S0)
(t-machine M1 T1)
(t-machine M9 T2 S1)
(run)
(t-expect-request "prod complete S2 beats making S1" finish-puck-at M9)

;; Completing a P beats completing an S2.
(reset)
(t-holding S1)
(t-machine M2 T2 S0)
(t-machine M8 T3 S0 S2)
(run)
(t-expect-request "prod complete P beats complete S2" finish-puck-at M8)

;; Second input of a T3 beats opening an empty T2.
(reset)
(t-holding S0)
(t-machine M2 T2)
(t-machine M6 T3 S1)
(run)
(t-expect-request "prod T3 progress beats T2 start" finish-puck-at M6)

;; An S1 is awaited (T2 holds S0): feed the T1 before opening a T3.
(reset)
(t-holding S0)
(t-machine M1 T1)
(t-machine M2 T2 S0)
(t-machine M5 T3)
(run)
(t-expect-request "prod feed T1 when an S1 is awaited" finish-puck-at M1)

;; Nothing awaits an S1: open the empty T2 rather than make an S1.
(reset)
(t-holding S0)
(t-machine M1 T1)
(t-machine M4 T2)
(t-machine M5 T3)
(run)
(t-expect-request "prod T2 start beats T3 start and T1" finish-puck-at M4)

;; An S2 opens an empty T3 rather than probe a T2_3.
(reset)
(t-holding S2)
(t-machine M3 T2_3 S0)
(t-machine M7 T3)
(run)
(t-expect-request "prod S2 opens empty T3" finish-puck-at M7)

;; An S2 with no T3 known probes the loaded T2_3 before unknown machines.
(reset)
(t-holding S2)
(t-machine M1 T1)
(t-machine M5 T2_3 S1)
(run)
(t-expect-request "prod S2 probes T2_3" finish-puck-at M5)

;; Production beats exploration: S0 goes to a known T1, not an unknown.
(reset)
(t-holding S0)
(t-machine M4 T1)
(run)
(t-expect-request "prod production beats exploration" finish-puck-at M4)

;; Exploration: everything unknown, the first machine in name order.
(reset)
(t-holding S1)
(run)
(t-expect-request "prod explore first unknown" finish-puck-at M1)

;; Exploration with S0 also probes a T1_2 (same priority, name order).
(reset)
(t-holding S0)
(t-machine M1 T2_3 S0)
(t-machine M2 T1_2)
(run)
(t-expect-request "prod explore T1_2 in name order" finish-puck-at M2)

;; Equal priority: ties go to the lower machine index, not agenda order.
(reset)
(t-holding S0)
(t-machine M7 T2_3 S1)
(t-machine M3 T2_3 S1)
(t-machine M10 T2_3 S1)
(run)
(t-expect-request "prod tie by name: M3 of M3/M7/M10" finish-puck-at M3)

;; A P is delivered to the active gate.
(reset)
(assert (active-gate D2))
(t-holding P)
(run)
(t-expect-request "prod deliver P to active gate" deliver D2)

;; A puck nothing can use is discarded at the nearest recycling unit.
(reset)
(t-holding S2)
(t-at M9)
;; One command per line: CLIPS's batch mode drops the rest of a line after a command.
(t-machine M1 T1)
(t-machine M2 T1)
(t-machine M3 T1)
(t-machine M4 T1)
(t-machine M5 T1)
(t-machine M6 T1)
(t-machine M7 T1)
(t-machine M8 T1)
(t-machine M9 T1)
(t-machine M10 T1)
(run)
(t-expect-request "prod discard unusable S2 at nearest recycling" discard R2)
