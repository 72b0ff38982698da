; logical over templates with not and exists CEs: modify takes support away, a
; fact with several supports stays until the last goes, reset cascades in order
(watch activations)
(watch facts)
(watch rules)
(deftemplate task (slot id) (slot state (default open)))
(deftemplate robot (slot name) (slot busy (default no)))
(defrule want-help
  (logical (task (id ?t) (state open))
           (robot (name ?r) (busy no)))
  =>
  (assert (offer ?r ?t)))
(defrule accept
  (logical (offer ?r ?t)
           (not (taken ?t)))
  =>
  (assert (plan ?r ?t)))
(defrule no-robots
  (logical (not (robot)))
  =>
  (assert (alarm no-robots)))
(defrule any-offer
  (logical (exists (offer ? ?)))
  =>
  (assert (have-offers)))
(defrule two-support
  (logical (plan ?r ?t))
  =>
  (assert (status busy)))
(deffacts start (task (id t1)) (task (id t2)))
(reset)
(run)
(assert (robot (name r1)) (robot (name r2)))
(run)
(facts)
(dependencies 13)
(dependents 4)
(dependencies 8)
(dependents 12)
(modify 5 (busy yes))
(facts)
(assert (taken t1))
(run)
(facts)
(retract 1 2)
(facts)
(modify 4 (busy yes))
(run)
(facts)
(reset)
(facts)
(exit)
