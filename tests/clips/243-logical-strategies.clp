; logical with not over several CEs, a test CE, or CEs, and every strategy
(watch activations)
(watch facts)
(watch rules)
(defrule safe
  (logical (zone ?z)
           (not (and (hazard ?z ?k) (active ?k)))
           (test (neq ?z off)))
  =>
  (assert (safe ?z)))
(defrule either
  (logical (or (alpha ?x) (beta ?x)))
  =>
  (assert (seen ?x)))
(defrule chain
  (logical (seen ?x))
  (not (stop))
  =>
  (assert (chain ?x 1))
  (assert (chain ?x 2)))
(defrule chain2
  (logical (chain ?x ?n))
  =>
  (assert (deep ?x ?n)))
(defrule retract-self
  (logical ?f <- (kill ?x))
  =>
  (retract ?f)
  (assert (after-kill ?x))
  (assert (alpha ?x)))
(defrule plain-rule
  (plain ?x)
  =>
  (assert (seen ?x)))
(reset)
(set-strategy breadth)
(assert (zone a) (zone b) (zone off) (hazard a h1) (hazard b h2))
(run)
(assert (active h1))
(assert (alpha 1) (beta 1) (beta 2))
(run)
(dependencies 9)
(retract 7)
(facts)
(retract 8)
(facts)
(assert (plain 2))
(run)
(retract 9)
(facts)
(set-strategy lex)
(assert (kill 5) (alpha 6) (beta 7))
(run)
(facts)
(set-strategy mea)
(assert (stop))
(assert (alpha 8))
(run)
(retract 1)
(assert (zone c))
(run)
(set-strategy complexity)
(retract 6)
(assert (beta 9))
(run)
(set-strategy simplicity)
(reset)
(facts)
(exit)
