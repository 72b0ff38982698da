; A rule added while facts exist: each new join under an older one is primed from
; the memory of its newest older sibling (CLIPS keeps one per join), bucket by
; bucket, each copy entering the new join's memory at its head; a later right
; activation of the new join meets its memory in that order.
(deftemplate it (slot id) (slot v))
(deftemplate mk (slot v))
(watch activations)
(defrule r1 (it (id ?i)) (not (mk (v z))) => )
(assert (it (id 1)) (it (id 2)) (it (id 3)) (it (id 4)))
; primed from r1's not join: its memory is the reverse of r1's
(defrule r2 (it (id ?i)) (exists (mk (v x))) => )
; primed from r2's exists join, the newest older sibling
(defrule r3 (it (id ?i)) => )
; right activation of r2's exists join: its own order
(assert (mk (v x)))
(assert (it (id 5)))
(defrule r4 (declare (salience 5)) (it (id ?i)) (mk (v x)) => )
(defrule r5 (declare (salience 6)) (it (id ?i)) (not (mk (v y))) => )
(agenda)
; hashed left memories: a join comparing ?k with an earlier variable keeps its
; partial matches in buckets of the values' symbol-table hash
(deftemplate p (slot k) (slot n))
(deftemplate q (slot k))
(deftemplate s (slot k))
(defrule h1 (p (k ?k) (n ?n)) (q (k ?k)) => )
(assert (p (k alpha) (n 1)) (p (k 7) (n 2)) (p (k "str") (n 3)) (p (k beta) (n 4))
        (p (k 2.5) (n 5)) (p (k gamma) (n 6)) (p (k -12) (n 7)) (p (k delta) (n 8)))
(defrule h2 (p (k ?k) (n ?n)) (not (q (k ?k))) => )
(defrule h3 (p (k ?k) (n ?n)) (s (k ?n)) => )
(defrule h4 (p (k ?k) (n ?n)) => )
(assert (s (k 3)) (q (k alpha)))
(defrule h5 (p (k ?k) (n ?n)) (exists (s (k ?k))) => )
(assert (s (k alpha)) (s (k 7)) (s (k beta)))
; several compared fields: the last one's bucket counts once, each earlier one 509
; times more
(deftemplate t3 (slot a) (slot b) (slot c))
(deftemplate u3 (slot a) (slot b) (slot c))
(defrule k1 (t3 (a ?a) (b ?b) (c ?c)) (u3 (a ?a) (b ?b) (c ?c)) => )
(assert (t3 (a 1) (b 2) (c 3)) (t3 (a 3) (b 2) (c 1)) (t3 (a 5) (b 11) (c 4))
        (t3 (a 0) (b 0) (c 9)) (t3 (a 9) (b 0) (c 0)) (t3 (a x) (b y) (c z))
        (t3 (a z) (b y) (c x)) (t3 (a 16) (b 1) (c 2)) (t3 (a 2) (b 16) (c 1)))
(defrule k2 (t3 (a ?a) (b ?b) (c ?c)) => )
(defrule k3 (t3 (a ?a) (b ?b) (c ?c)) (u3 (a ?c) (b ?a)) => )
(defrule k4 (t3 (a ?a) (b ?b) (c ?c)) => )
(deftemplate t2 (slot a) (slot b))
(deftemplate u2 (slot a) (slot b))
(defrule m1 (t2 (a ?a) (b ?b)) (u2 (a ?a) (b ?b)) => )
(assert (t2 (a 1) (b 2)) (t2 (a 2) (b 1)) (t2 (a 0) (b 5)) (t2 (a 5) (b 0)) (t2 (a 3) (b 3)))
(defrule m2 (t2 (a ?a) (b ?b)) => )
(run)
(exit)
