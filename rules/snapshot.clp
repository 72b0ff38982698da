;;; snapshot.clp -- nothing lost on restart: a snapshot after every decision.
;;;
;;; When the host asserts (snapshot-file "PATH"), every logged decision
;;; (game-log.clp) is followed by (save-facts "PATH") of the whole fact base
;;; -- the agent's beliefs, and in a simulated game also the referee's
;;; ground truth, the simulation and the decision log -- then by a line
;;; "SNAPSHOT n PATH" that tells the host the file is complete (so it can
;;; replace the previous snapshot atomically).  It runs after the decision
;;; is logged and before production picks the next action, so a process
;;; that loads the snapshot into freshly loaded rules (no (reset)) goes on
;;; exactly where the saved one stood.  Without a snapshot-file fact the
;;; rule never fires.

(defglobal ?*PRIORITY_SNAPSHOT* = 55)   ; after the log (60), before candidates (50)

(defrule snapshot-after-decision
  (declare (salience ?*PRIORITY_SNAPSHOT*))
  (snapshot-file ?path)
  (decision (n ?n))
  (not (snapshot-saved ?m&:(>= ?m ?n)))
  =>
  (do-for-all-facts ((?s snapshot-saved)) TRUE (retract ?s))
  (assert (snapshot-saved ?n))
  (save-facts ?path)
  (printout t "SNAPSHOT " ?n " " ?path crlf))
