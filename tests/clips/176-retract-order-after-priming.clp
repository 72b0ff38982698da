; A rule defined while a fact exists, sharing its alpha memory with an older rule: when
; the fact goes, CLIPS removes the newer rule's activation first (its match is the newer
; one, made by priming), then the older rules' in their order.
(deftemplate it (slot id) (slot w))
(defrule q (it (w ?w)) =>)
(assert (it (id 1) (w 5)))
(watch activations)
(defrule r (it (id ?i)) =>)
(defrule s (it (id 1)) =>)
(retract 1)
(exit)
