;;; strategy: naive
;;; The naive baseline: first machine in name order that may take the puck.

(reset)
(t-holding S1)
(t-machine M1 T1)
(t-machine M2 T2 S1)
(run)
(t-expect-request "naive: skip machines that cannot take S1" finish-puck-at M3)

(reset)
(t-holding S0)
(t-machine M1 T2_3 S1)
(t-machine M9 T3 S1 S2)
(run)
(t-expect-request "naive: no priorities, first fit wins" finish-puck-at M1)
