; Rules primed from partial matches they share with older rules: when a fact goes,
; CLIPS removes the copies priming made first, the latest primed first, then the
; others, oldest rule first: three rules primed one after another, a rule defined
; before the fact among them, two-pattern rules sharing their first join, a fact
; asserted after the priming, and a retract of the second pattern's fact.
(deftemplate it (slot id) (slot w))
(deftemplate k (slot v))
(defrule q (it (w ?w)) =>)
(defrule q2 (it (id ?i) (w ?w)) (k (v ?w)) =>)
(assert (it (id 1) (w 5)))
(assert (k (v 5)))
(watch activations)
(defrule r (it (id ?i)) =>)
(defrule t (it) =>)
(defrule u (it (w ?x)) =>)
(defrule r2 (it (id ?i) (w ?w)) (k (v ?w)) =>)
(defrule r3 (it (id ?i) (w ?w)) (k (v ?v)) =>)
(assert (it (id 2) (w 5)))
(retract 2)
(retract 1)
(assert (it (id 3) (w 5)))
(retract 3)
(exit)
