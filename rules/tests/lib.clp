;;; lib.clp -- helpers for behaviour-level scenario tests (real CLIPS).
;;;
;;; A scenario: (reset), shape the beliefs with t-machine / t-holding /
;;; t-at, optionally hand the agent a skill outcome with t-outcome, (run),
;;; then check with t-expect-*.  Each check prints one PASS or FAIL line;
;;; run.sh counts them (globals would not survive the next (reset)).

(deffunction t-report (?ok ?label ?detail)
  (if ?ok
   then (printout t "PASS " ?label crlf)
   else (printout t "FAIL " ?label ": " ?detail crlf)))

(deffunction t-machine
  "Set a machine belief: type class and loaded pucks."
  (?name ?mtype $?loaded)
  (do-for-fact ((?m machine)) (eq ?m:name ?name)
    (modify ?m (mtype ?mtype) (loaded-with ?loaded))))

(deffunction t-holding (?puck)
  (do-for-all-facts ((?h holding)) TRUE (retract ?h))
  (assert (holding ?puck)))

(deffunction t-at (?place)
  (do-for-all-facts ((?r robot-at)) TRUE (retract ?r))
  (assert (robot-at ?place)))

(deffunction t-outcome
  "The agent committed to ?skill at ?target (request id 1) and the
   behaviour layer answers with ?status and ?light."
  (?skill ?target ?status ?light)
  (do-for-all-facts ((?s state)) TRUE (retract ?s))
  (do-for-all-facts ((?n next-skill-id)) TRUE (retract ?n))
  (bind ?puck NONE)
  (do-for-fact ((?h holding)) TRUE (bind ?puck (nth$ 1 ?h:implied)))
  (assert (state EXEC) (next-skill-id 2)
          (skill-request (id 1) (name ?skill) (target ?target) (puck ?puck))
          (skill-outcome (id 1) (status ?status) (light ?light))))

(deffunction t-outcome-sensed
  "Like t-outcome, with the gripper's puck sensor in info (puck-held or
   no-puck)."
  (?skill ?target ?status ?light ?info)
  (t-outcome ?skill ?target ?status ?light)
  (do-for-all-facts ((?o skill-outcome)) TRUE
    (modify ?o (info ?info))))

(deffunction t-expect-request
  "The agent's next committed skill is ?skill at ?target."
  (?label ?skill ?target)
  (bind ?got (create$))
  (do-for-all-facts ((?r skill-request)) TRUE
    (bind ?got (create$ ?got ?r:name ?r:target)))
  (t-report (eq (implode$ ?got) (implode$ (create$ ?skill ?target))) ?label
            (str-cat "expected request " ?skill " " ?target ", got ("
                     (implode$ ?got) ")")))

(deffunction t-expect-machine (?label ?name ?mtype $?loaded)
  (bind ?got nil)
  (do-for-fact ((?m machine)) (eq ?m:name ?name)
    (bind ?got (create$ ?m:mtype ?m:loaded-with)))
  (t-report (eq (implode$ ?got) (implode$ (create$ ?mtype ?loaded))) ?label
            (str-cat "expected " ?name " " (implode$ (create$ ?mtype ?loaded))
                     ", got " (implode$ ?got))))

(deffunction t-expect-junk (?label ?name ?junk ?productions)
  (bind ?got nil)
  (do-for-fact ((?m machine)) (eq ?m:name ?name)
    (bind ?got (create$ ?m:junk ?m:productions)))
  (t-report (eq (implode$ ?got) (implode$ (create$ ?junk ?productions))) ?label
            (str-cat "expected junk/productions " ?junk " " ?productions
                     ", got " (implode$ ?got))))

(deffunction t-expect-holding (?label ?puck)
  (bind ?got (create$))
  (do-for-all-facts ((?h holding)) TRUE (bind ?got (create$ ?got ?h:implied)))
  (t-report (eq (implode$ ?got) (implode$ (create$ ?puck))) ?label
            (str-cat "expected holding " ?puck ", got " (implode$ ?got))))

(deffunction t-expect-state (?label ?state)
  (bind ?got (create$))
  (do-for-all-facts ((?s state)) TRUE (bind ?got (create$ ?got ?s:implied)))
  (t-report (eq (implode$ ?got) (implode$ (create$ ?state))) ?label
            (str-cat "expected state " ?state ", got " (implode$ ?got))))

(deffunction t-expect-no-request (?label)
  (bind ?n (length$ (find-all-facts ((?r skill-request)) TRUE)))
  (t-report (= ?n 0) ?label (str-cat ?n " skill requests pending")))
