;;; report.clp -- CLIPS-only helpers for the drivers: print a game's result.

(deffunction report-decisions
  "One line per logged decision, in order."
  ()
  (bind ?n (length$ (find-all-facts ((?d decision)) TRUE)))
  (loop-for-count (?i 1 ?n)
    (do-for-fact ((?d decision)) (= ?d:n ?i)
      (format t "%4d %7.1f %-14s %-4s %-3s %-6s %-15s -> %-4s %3d  %s%n"
        ?d:n ?d:time ?d:action ?d:target ?d:puck ?d:status ?d:light
        ?d:holding ?d:points (implode$ ?d:beliefs)))))

(deffunction report-game
  "One summary line: points, products, end reason and time, decisions."
  ()
  (bind ?reason none) (bind ?time 0.0)
  (do-for-fact ((?g game-over)) TRUE (bind ?reason ?g:reason) (bind ?time ?g:time))
  (bind ?decisions (length$ (find-all-facts ((?d decision)) TRUE)))
  (bind ?metres 0.0)
  (do-for-fact ((?r sim-robot)) TRUE (bind ?metres ?r:travelled))
  (do-for-fact ((?s score)) TRUE
    (format t "RESULT points %d s1 %d s2 %d p %d delivered %d lost %d discarded %d recycled %d end %s time %.1f decisions %d travel %.1f%n"
      ?s:points ?s:s1 ?s:s2 ?s:p ?s:delivered ?s:lost ?s:discarded
      ?s:recycled ?reason ?time ?decisions ?metres)))
