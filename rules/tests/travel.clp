;;; strategy: travel
;;; Our travel-aware commitment: equal priority -> nearest machine.

(reset)
(t-holding S0)
(t-at M10)
(t-machine M3 T2_3 S1)
(t-machine M9 T2_3 S1)
(run)
(t-expect-request "travel: nearest of equal candidates" finish-puck-at M9)

;; Priorities still come first: a far T2 completion beats a near T1.
(reset)
(t-holding S0)
(t-at M10)
(t-machine M7 T1)
(t-machine M3 T2 S1)
(run)
(t-expect-request "travel: priority before distance" finish-puck-at M3)

;; Exploration from the input storage: the nearest unknown machine.
(reset)
(t-holding S0)
(t-at INS)
(run)
(t-expect-request "travel: explore nearest unknown" finish-puck-at M8)
