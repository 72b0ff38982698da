; A rule starting with (not (and ...)) or (exists (and ...)) whose subnetwork is
; shared with an earlier rule, defined while that subnetwork has partial matches:
; CLIPS primes its join from the right with copies of them, younger than the copies
; the earlier rule holds. A retract takes the copies back youngest first: the new
; rule's unblock (or loss) comes before the earlier rule's activation goes.
(watch activations)
(assert (o 3 1) (a 3) (a 4) (k 1))
(defrule r2 (o 3 ?x) (a ?z) =>)
(defrule r3 (not (and (o 3 ?x) (a ?z))) =>)
(defrule r4 (exists (and (o 3 ?x) (a ?z))) =>)
(defrule r5 (not (and (o 3 ?x) (a ?z))) (k ?w) =>)
(retract 2)
(retract 3)
(assert (a 5))
(retract 1)
(assert (o 3 2))
(defrule r6 (exists (and (o 3 ?x) (a ?z))) (k ?w) =>)
(retract 6)
(exit)
