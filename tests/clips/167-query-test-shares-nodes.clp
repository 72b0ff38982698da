; A rule whose test or constraint runs a fact-set query shares the network nodes of an
; identical earlier one even after the query ran (its lookup caches are not part of the
; expression): the shared join's memory decides the new rule's activations, as in CLIPS.
(deftemplate cnt (slot c))
(watch compilations)
(watch activations)
(defrule a (cnt (c ?x)) (test (any-factp ((?k cnt)) (> ?k:c ?x))) =>)
(assert (cnt (c 1)) (cnt (c 2)))
(defrule b (cnt (c ?x)) (test (any-factp ((?k cnt)) (> ?k:c ?x))) =>)
(defrule c (cnt (c ?x&:(any-factp ((?k cnt)) (> ?k:c ?x)))) =>)
(assert (cnt (c 0)))
(defrule d (cnt (c ?x&:(any-factp ((?k cnt)) (> ?k:c ?x)))) =>)
(agenda)
(exit)
