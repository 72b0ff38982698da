;;; strategy: paper
;;; World model: after finish-puck-at ends FINAL with a light, what the
;;; robot holds and what it believes about the machine; one scenario per
;;; rule group (light -> holding, green, yellow, yellow-flashing, unexplained).

;; Paper, Figure 4: S0 to a T2_3 loaded with S1, green -> S2 and a T2.
(reset)
(t-holding S0)
(t-machine M3 T2_3 S1)
(t-outcome finish-puck-at M3 FINAL green)
(run)
(t-expect-holding "wm green at T2_3+S1: holding S2" S2)
(t-expect-machine "wm green at T2_3+S1: machine is T2, emptied" M3 T2)
(t-expect-junk "wm green at T2_3+S1: one junk, one production" M3 1 1)

;; Green on the first S0 at an unknown machine: a T1 made S1.
(reset)
(t-holding S0)
(t-outcome finish-puck-at M5 FINAL green)
(run)
(t-expect-holding "wm green first input: holding S1" S1)
(t-expect-machine "wm green first input: T1" M5 T1)
(t-expect-junk "wm green first input: no junk" M5 0 1)

;; Green on the third input: a P and two junk.
(reset)
(t-holding S1)
(t-machine M2 T3 S0 S2)
(t-outcome finish-puck-at M2 FINAL green)
(run)
(t-expect-holding "wm green third input: holding P" P)
(t-expect-machine "wm green third input: T3 emptied" M2 T3)
(t-expect-junk "wm green third input: two junk" M2 2 1)

;; Yellow on the first S0 at an unknown machine: T2_3 loaded with S0.
(reset)
(t-holding S0)
(t-outcome finish-puck-at M4 FINAL yellow)
(run)
(t-expect-holding "wm yellow first S0: hands empty" NONE)
(t-expect-machine "wm yellow first S0: T2_3+S0" M4 T2_3 S0)

;; Yellow on a second input: a T2 would have finished, so a T3.
(reset)
(t-holding S1)
(t-machine M4 T2_3 S0)
(t-outcome finish-puck-at M4 FINAL yellow)
(run)
(t-expect-machine "wm yellow second input: T3+S0+S1" M4 T3 S0 S1)

;; Yellow on an S2: only a T3 takes one.
(reset)
(t-holding S2)
(t-outcome finish-puck-at M6 FINAL yellow)
(run)
(t-expect-machine "wm yellow S2 at unknown: T3+S2" M6 T3 S2)

;; Yellow at a T1_2: it waits for more, so a T2.
(reset)
(t-holding S1)
(t-machine M6 T1_2)
(t-outcome finish-puck-at M6 FINAL yellow)
(run)
(t-expect-machine "wm yellow at T1_2: T2+S1" M6 T2 S1)

;; Yellow at a known empty T2: just loaded.
(reset)
(t-holding S0)
(t-machine M6 T2)
(t-outcome finish-puck-at M6 FINAL yellow)
(run)
(t-expect-machine "wm yellow at known T2: loaded" M6 T2 S0)

;; Flashing S1 at an unknown machine: a T1; the robot keeps the S1.
(reset)
(t-holding S1)
(t-outcome finish-puck-at M7 FINAL yellow-flashing)
(run)
(t-expect-holding "wm flash S1 unknown: keeps S1" S1)
(t-expect-machine "wm flash S1 unknown: T1" M7 T1)

;; Flashing S2 at an unknown machine: not a T3.
(reset)
(t-holding S2)
(t-outcome finish-puck-at M7 FINAL yellow-flashing)
(run)
(t-expect-holding "wm flash S2 unknown: keeps S2" S2)
(t-expect-machine "wm flash S2 unknown: T1_2" M7 T1_2)

;; Flashing S2 at a T2_3 holding an S0: a T2.
(reset)
(t-holding S2)
(t-machine M8 T2_3 S0)
(t-outcome finish-puck-at M8 FINAL yellow-flashing)
(run)
(t-expect-machine "wm flash S2 at T2_3+S0: T2 keeps its S0" M8 T2 S0)

;; Flashing where the beliefs predicted it: nothing changes.
(reset)
(t-holding S0)
(t-machine M8 T2 S0)
(t-outcome finish-puck-at M8 FINAL yellow-flashing)
(run)
(t-expect-machine "wm flash predicted: belief unchanged" M8 T2 S0)
(t-expect-holding "wm flash predicted: keeps S0" S0)

;; Yellow at a believed T1: a T1 never waits, the belief was wrong.
(reset)
(t-holding S0)
(t-machine M9 T1)
(t-outcome finish-puck-at M9 FINAL yellow)
(run)
(t-expect-machine "wm yellow at T1 contradicts: T2_3 holding the S0" M9 T2_3 S0)

;; Yellow for a second input at a believed T2: it was empty after all.
(reset)
(t-holding S1)
(t-machine M9 T2 S1)
(t-outcome finish-puck-at M9 FINAL yellow)
(run)
(t-expect-machine "wm yellow at loaded T2 contradicts: T2 holding the S1" M9 T2 S1)

;; A light the beliefs cannot explain: forget the machine's contents.
(reset)
(t-holding S0)
(t-machine M9 T2_3)
(t-outcome finish-puck-at M9 FINAL green)
(run)
(t-expect-machine "wm unexplained green at empty T2_3: belief reset" M9 T1_2_3)
(t-expect-holding "wm unexplained green: puck kind unknown" UNKNOWN)

;; Green at a known type with stale contents: the type says the output.
(reset)
(t-holding S1)
(t-machine M9 T3)
(t-outcome finish-puck-at M9 FINAL green)
(run)
(t-expect-holding "wm green at a known T3: holding P whatever was loaded" P)

;; The camera says flashing but the gripper is empty: the machine took it (yellow).
(reset)
(t-holding S0)
(t-outcome-sensed finish-puck-at M4 FINAL yellow-flashing no-puck)
(run)
(t-expect-machine "wm misread flashing, empty gripper: read as yellow" M4 T2_3 S0)
(t-expect-holding "wm misread flashing, empty gripper: holds nothing" NONE)

;; The camera says yellow but the gripper holds a puck; the belief settles it.
(reset)
(t-holding S1)
(t-machine M4 T1)
(t-outcome-sensed finish-puck-at M4 FINAL yellow puck-held)
(run)
(t-expect-machine "wm misread yellow, T1 rejects S1: belief unchanged" M4 T1)
(t-expect-holding "wm misread yellow, T1 rejects S1: keeps S1" S1)

(reset)
(t-holding S2)
(t-machine M4 T3 S0 S1)
(t-outcome-sensed finish-puck-at M4 FINAL yellow puck-held)
(run)
(t-expect-holding "wm misread yellow, S2 completes a T3: holding P" P)
(t-expect-machine "wm misread yellow, S2 completes a T3: emptied" M4 T3)

;; A T2_3 holding an S1 takes an S0 whatever it is: the puck held is an output (green).
(reset)
(t-holding S0)
(t-machine M4 T2_3 S1)
(t-outcome-sensed finish-puck-at M4 FINAL yellow puck-held)
(run)
(t-expect-machine "wm misread yellow, S0 cannot be rejected: green, a T2" M4 T2)
(t-expect-holding "wm misread yellow, S0 cannot be rejected: holding S2" S2)

;; ... and where the belief cannot settle it: contents and puck unknown, discard.
(reset)
(t-holding S1)
(t-machine M4 T1_2)
(t-outcome-sensed finish-puck-at M4 FINAL yellow puck-held)
(run)
(t-expect-machine "wm misread yellow, unsettled: contents forgotten, type kept" M4 T1_2)
(t-expect-request "wm misread yellow, unsettled: discard the unknown puck" discard R1)

(reset)
(t-holding S1)
(t-machine M4 T2_3 S0)
(t-machine M5 T1)
(t-outcome-sensed finish-puck-at M4 FINAL yellow puck-held)
(run)
(t-expect-holding "wm misread yellow, S1 at T2_3+S0 cannot be rejected: S2" S2)

;; Flashing S1 at a known T2 believed empty: the S1 is already there.
(reset)
(t-holding S1)
(t-machine M5 T2)
(t-outcome finish-puck-at M5 FINAL yellow-flashing)
(run)
(t-expect-machine "wm flash S1 at empty T2: S1 already loaded" M5 T2 S1)

;; Flashing S0 at a believed T1: a T1 never keeps pucks, so it is a T2/T3.
(reset)
(t-holding S0)
(t-machine M5 T1)
(t-outcome finish-puck-at M5 FINAL yellow-flashing)
(run)
(t-expect-machine "wm flash S0 at T1 contradicts: T2_3 holding S0" M5 T2_3 S0)

;; Flashing S0 at a machine believed empty: an S0 must already be there.
(reset)
(t-holding S0)
(t-outcome finish-puck-at M10 FINAL yellow-flashing)
(run)
(t-expect-machine "wm flash S0: an S0 was already loaded" M10 T2_3 S0)
(t-expect-holding "wm flash S0: keeps S0" S0)
