;;; lib-game.clp -- scenario helpers that need the referee and sim
;;; templates (loaded for test files with ";;; with: game").

;;; ---- referee and whole-game checks (files with ";;; with: game") ----

(deffunction t-quiet-agent
  "Remove the agent's state so only the referee and sim act."
  ()
  (do-for-all-facts ((?s state)) TRUE (retract ?s)))

(deffunction t-expect-result (?label ?id ?status ?light ?puck)
  (bind ?got nil)
  (do-for-fact ((?r rf-result)) (= ?r:id ?id)
    (bind ?got (create$ ?r:status ?r:light ?r:puck)))
  (t-report (eq (implode$ ?got) (implode$ (create$ ?status ?light ?puck))) ?label
            (str-cat "expected " ?status " " ?light " " ?puck ", got "
                     (implode$ ?got))))

(deffunction t-expect-rf-machine (?label ?name $?loaded)
  (bind ?got nil)
  (do-for-fact ((?m rf-machine)) (eq ?m:name ?name) (bind ?got ?m:loaded-with))
  (t-report (eq (implode$ ?got) (implode$ ?loaded)) ?label
            (str-cat "expected " ?name " loaded (" (implode$ ?loaded)
                     "), got (" (implode$ ?got) ")")))

(deffunction t-expect-score (?label ?points ?p)
  (bind ?got nil)
  (do-for-fact ((?s score)) TRUE (bind ?got (create$ ?s:points ?s:p)))
  (t-report (eq (implode$ ?got) (implode$ (create$ ?points ?p))) ?label
            (str-cat "expected points/P " ?points " " ?p ", got " (implode$ ?got))))

(deffunction t-expect-game-over (?label ?reason)
  (bind ?got nil)
  (do-for-fact ((?g game-over)) TRUE (bind ?got ?g:reason))
  (t-report (eq ?got ?reason) ?label
            (str-cat "expected game over by " ?reason ", got " ?got)))
