;;; Negation-heavy scaling workload: jobs start only when the job they wait
;;; for is no longer pending and their crew is not busy. Starting a job makes
;;; its crew busy and freeing the crew unblocks its other jobs again, so every
;;; firing re-evaluates `not` conditions for a whole crew. Jobs and pending
;;; facts come from the data generator (robotino-agent bench,
;;; host-shim/src/bench/workloads.rs). The global folds the start order into
;;; one number so the engines' final lines can be compared.

(defglobal ?*order* = 0 ?*started* = 0)

(deftemplate job (slot id) (slot after) (slot crew))
(deftemplate pending (slot id))
(deftemplate busy (slot crew))

(defrule start_job
   ?p <- (pending (id ?i))
   (job (id ?i) (after ?d) (crew ?c))
   (not (pending (id ?d)))
   (not (busy (crew ?c)))
   =>
   (retract ?p)
   (bind ?*started* (+ ?*started* 1))
   (bind ?*order* (mod (+ (* ?*order* 31) ?i) 1000000007))
   (assert (busy (crew ?c))))

(defrule free_crew
   (declare (salience 10))
   ?b <- (busy (crew ?c))
   =>
   (retract ?b))

(defrule all_started
   (declare (salience -100))
   (not (pending (id ?)))
   =>
   (printout t "started " ?*started* " order " ?*order* crlf))
