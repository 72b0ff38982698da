; A pattern test that fails with an error on a CLIPS pattern-network node several
; patterns share (the same slots and tests up to it, a multislot after it): one
; [FACTMCH1] block for the node, naming every rule below it (newest first), whatever
; the multislot holds, even when it is too short for every pattern (its length is
; tested at its own node, after the failing one). Where a pattern ends at the failing
; node (or at a node between), only its rules are named, not the longer patterns'
; below it. Which facts match stays the same.
(deftemplate robot (slot name) (slot x (default 0)) (multislot tags))
(defrule not-tag
  (robot (name ?n) (x ?x&:(> ?x 2)) (tags ?t&~far $?))
  =>
  (printout t "not-tag " ?n " " ?t crlf))
(defrule not-second-tag
  (robot (name ?n) (x ?x&:(> ?x 2)) (tags ? ?t&~far))
  =>
  (printout t "not-second-tag " ?n " " ?t crlf))
(assert (robot (name r7) (x abc) (tags a b)))
(assert (robot (name r8) (x abc) (tags)))
(assert (robot (name r9) (x abc) (tags a)))
(assert (robot (name r10) (x 5) (tags a b)))
(run)
; a third rule sharing the node, defined later: its priming tests the node again
(defrule third-tag
  (robot (name ?n) (x ?x&:(> ?x 2)) (tags ? ? ?t))
  =>
  (printout t "third-tag " ?n " " ?t crlf))
(assert (robot (name r11) (x abc) (tags a b c)))
(run)
; ordered facts: a field test before a multifield
(defrule o1 (d ?x&:(> ?x 2) a $?) => (printout t "o1 " ?x crlf))
(defrule o2 (d ?x&:(> ?x 2) b c) => (printout t "o2 " ?x crlf))
(assert (d abc a))
(assert (d abc))
(assert (d abc b c))
(assert (d 3 b c))
(run)
; a pattern ending at the failing node hides the longer ones below it
(deftemplate t (slot x) (slot y) (multislot m))
(defrule a (t (x ?x&:(> ?x 2)) (y 1) (m a)) => (printout t "a" crlf))
(defrule b (t (x ?x&:(> ?x 2)) (y 1) (m a b)) => (printout t "b" crlf))
(defrule c (t (x ?x&:(> ?x 2)) (y 2) (m)) => (printout t "c" crlf))
(defrule d (t (x ?x&:(> ?x 2))) => (printout t "d" crlf))
(assert (t (x abc) (y 1)))
(assert (t (x abc) (y 2) (m a)))
(defrule e (t (x ?x&:(> ?x 2)) (y 1) (m a b c)) => (printout t "e" crlf))
(assert (t (x abc) (y 3) (m q)))
(assert (t (x 4) (y 1) (m a b)))
(run)
; ... and one ending between: (y 5) ends there, the (m ...) patterns below it are not named
(deftemplate u (slot x) (slot y) (multislot m))
(defrule u1 (u (x ?x&:(> ?x 2)) (y 5)) => (printout t "u1" crlf))
(defrule u2 (u (x ?x&:(> ?x 2)) (y 5) (m a)) => (printout t "u2" crlf))
(defrule u3 (u (x ?x&:(> ?x 2)) (y 6) (m a)) => (printout t "u3" crlf))
(assert (u (x abc) (y 5) (m a)))
(assert (u (x 7) (y 5) (m a)))
(run)
(exit)
