;;; production-naive.clp -- the baseline strategy: no priorities.
;;;
;;; The held puck goes to the first machine in the fixed order M1..M10
;;; that may still take it according to the beliefs (some possible type
;;; has it as an input and it is not loaded there yet).  Same world model
;;; and execution monitoring as the paper's agent; only the choice differs.

(deffunction naive-may-take
  "TRUE if some type the belief allows consumes ?puck and it is not loaded."
  (?belief ?puck $?loaded)
  (if (member$ ?puck ?loaded) then (return FALSE))
  (switch ?puck
    (case S0 then TRUE)
    (case S1 then (or (mtype-may-be ?belief T2) (mtype-may-be ?belief T3)))
    (case S2 then (mtype-may-be ?belief T3))
    (default FALSE)))

(deffunction naive-target
  "The first machine in name order that may take ?puck, or nil."
  (?puck)
  (loop-for-count (?i 1 10)
    (bind ?found nil)
    (do-for-fact ((?m machine))
        (and (= ?m:index ?i) (naive-may-take ?m:mtype ?puck ?m:loaded-with))
      (bind ?found ?m:name))
    (if (neq ?found nil) then (return ?found)))
  nil)

(defrule naive-first-machine
  (declare (salience ?*PRIORITY_CANDIDATE*))
  (state IDLE)
  (holding ?x&S0|S1|S2)
  ?g <- (goto (machines))
  =>
  (bind ?target (naive-target ?x))
  (if (neq ?target nil)
   then (retract ?g)
        (assert (intent (action finish-puck-at) (target ?target)))))
