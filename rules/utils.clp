;;; utils.clp -- utilities of the LLSF agent: priorities and helper functions.
;;;
;;; Rule priorities (saliences) are globals so every file orders itself
;;; against the others in one place.  Higher fires first.  Machine
;;; priorities (PRIO_*) rank production targets: completing a higher
;;; valued sub-goal beats starting one, and production beats exploration.

(defglobal
  ;; saliences of the rule groups
  ?*PRIORITY_REFEREE* = 500     ; the game model answers at once
  ?*PRIORITY_WM_LIGHT* = 300    ; light -> what the robot holds now
  ?*PRIORITY_WM* = 200          ; world model evaluation -> machine beliefs
  ?*PRIORITY_WM_CLEANUP* = 150  ; unhandled evaluation, back to IDLE
  ?*PRIORITY_EXEC* = 100        ; execution monitoring
  ?*PRIORITY_LOG* = 60          ; simulation: decision log after beliefs settle
  ?*PRIORITY_RECYCLE* = 55      ; production: junk to recycle before a raw puck
  ?*PRIORITY_CANDIDATE* = 50    ; production: collect candidate targets
  ?*PRIORITY_SELECT* = 40       ; production: commit to one candidate
  ?*PRIORITY_FALLBACK* = 30     ; production: nothing fits the held puck
  ?*PRIORITY_DONE* = 20         ; nothing left to do
  ?*PRIORITY_SIM* = -10         ; simulation executes a committed skill
  ?*PRIORITY_DEADLOCK* = -1000  ; idle and no decision: a bug

  ;; machine priorities of production targets
  ?*PRIO_COMPLETE_P* = 60       ; the held puck completes a P at a T3
  ?*PRIO_COMPLETE_S2* = 50      ; the held puck completes an S2 at a T2
  ?*PRIO_RESOLVE_T23* = 45      ; complement at a T2_3: S2 or T3 progress
  ?*PRIO_T3_PROGRESS* = 40      ; second input of a T3
  ?*PRIO_FEED_S1* = 35          ; S0 to a T1 because an S1 is awaited
  ?*PRIO_T2_START* = 30         ; first input of an empty T2
  ?*PRIO_T3_START_S2* = 30      ; S2 opens an empty T3
  ?*PRIO_T3_START* = 25         ; S0/S1 opens an empty T3
  ?*PRIO_T1* = 20               ; S0 to a known T1
  ?*PRIO_EXPLORE_T23* = 15      ; S2 to a loaded T2_3: T3 or T2
  ?*PRIO_EXPLORE* = 10          ; a puck to a machine of unknown type

  ;; robot speed for travel estimates (m/s)
  ?*ROBOT_SPEED* = 0.5
)

;;; The field map: approach poses (m) of the machines, the input storage
;;; (INS), the delivery gates (D1..D3) and the recycling units (R1, R2).
(deftemplate place
  (slot name (type SYMBOL))
  (slot x (type NUMBER))
  (slot y (type NUMBER)))

;;; A type belief is a symbol naming the types still possible:
;;; T1_2_3 (unknown), T1_2, T2_3, or a single type T1, T2, T3.
(deffunction mtype-may-be
  "TRUE if the belief still allows the type (T1, T2 or T3)."
  (?belief ?type)
  (neq (str-index (sub-string 2 2 ?type) ?belief) FALSE))

(deffunction type-output (?type)
  (switch ?type
    (case T1 then S1)
    (case T2 then S2)
    (case T3 then P)
    (default NONE)))

(deffunction type-for-input-count
  "Green after the n-th input: the machine consumed n inputs, so its type is Tn."
  (?n)
  (switch ?n
    (case 1 then T1)
    (case 2 then T2)
    (case 3 then T3)
    (default NONE)))

(deffunction green-output
  "What the robot holds after green at a machine believed ?belief with
   ?loaded pucks believed loaded: a known type makes its output; otherwise
   the n-th input makes the output of Tn, if the belief allows Tn.  UNKNOWN
   when the belief contradicts the light (it lost track of the machine)."
  (?belief ?loaded)
  (if (member$ ?belief (create$ T1 T2 T3))
   then (return (type-output ?belief)))
  (bind ?type (type-for-input-count (+ 1 ?loaded)))
  (if (and (neq ?type NONE) (mtype-may-be ?belief ?type))
   then (type-output ?type)
   else UNKNOWN))

(deffunction every-type-takes
  "TRUE if every type the belief allows takes puck ?x as an input."
  (?belief ?x)
  (switch ?x
    (case S0 then TRUE)
    (case S1 then (not (mtype-may-be ?belief T1)))
    (case S2 then (and (not (mtype-may-be ?belief T1))
                       (not (mtype-may-be ?belief T2))))
    (default FALSE)))

(deffunction loaded-after
  "The loaded pucks after ?x is consumed without output at a machine of
   type belief ?belief: a T2 holds at most one, a T3 two; more (or ?x
   already there) means the old list was wrong, and only ?x is certain."
  (?belief ?lw ?x)
  (bind ?cap (if (eq ?belief T2) then 1 else 2))
  (if (or (>= (length$ ?lw) ?cap) (member$ ?x ?lw))
   then (create$ ?x)
   else (create$ ?lw ?x)))

(deffunction merge
  "Merge a candidate into the target list: a higher priority replaces the
   list, an equal one joins it."
  (?min-prio ?prio ?name $?machines)
  (if (> ?prio ?min-prio)
   then (create$ ?name)
   else (create$ ?machines ?name)))

(deffunction place-distance
  "Straight-line distance (m) between the approach poses of two places;
   0.0 if either place is unknown."
  (?from ?to)
  (bind ?x1 nil) (bind ?y1 nil) (bind ?x2 nil) (bind ?y2 nil)
  (do-for-fact ((?p place)) (eq ?p:name ?from) (bind ?x1 ?p:x) (bind ?y1 ?p:y))
  (do-for-fact ((?p place)) (eq ?p:name ?to) (bind ?x2 ?p:x) (bind ?y2 ?p:y))
  (if (or (eq ?x1 nil) (eq ?x2 nil))
   then (return 0.0))
  (distance ?x1 ?y1 ?x2 ?y2))
