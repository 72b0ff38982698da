; each branch of an or binds the same fact-address variable
(deftemplate cave (slot x) (slot safe) (slot has-pit))
(defrule safe-cave
  (or ?f <- (cave (x ?x) (safe TRUE) (has-pit ~FALSE))
      ?f <- (cave (x ?x) (safe MAYBE)))
  =>
  (printout t "fix " ?x crlf)
  (modify ?f (has-pit FALSE) (safe TRUE)))
(defrule three
  (go)
  (or (a ?v)
      ?g <- (b ?v)
      (and ?g <- (c ?v) (d ?v)))
  =>
  (printout t "three " ?v crlf))
(assert (cave (x 1) (safe TRUE) (has-pit UNKNOWN)) (cave (x 2) (safe MAYBE)))
(run)
(facts)
(assert (go) (a 1) (b 2) (c 3) (d 3) (c 4))
(run)
(exit)
