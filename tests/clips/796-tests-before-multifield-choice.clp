; CLIPS tests a pattern's nodes before the node where it chooses a multifield's
; length once, and the nodes between two such choices once per choice above them:
; a test's side effects and errors (one report naming every rule through the node)
; show how often it ran. Tests named after the multislot run per segmentation; a
; multislot too short still lets the tests before it run; new rules meet the facts.
(deftemplate t (slot x) (slot y) (multislot m) (multislot n))
(deffunction p (?v) (printout t "test " ?v crlf) TRUE)
; a test before the multifield choices runs once, one between them once per choice above it
(defrule a (t (x ?x&:(p ?x)) (m $?a ?b&:(p ?b) $?c ?d&:(p ?d) $?e)) => (printout t "a " ?a ?b ?c ?d ?e crlf))
(assert (t (x 1) (m 1 2 3 4)))
(run)
; the same test named after the multislot: once per segmentation
(defrule b (t (m $?a ?b $?c) (x ?x&:(p ?x))) => (printout t "b " ?a ?b ?c crlf))
(assert (t (x 2) (m 5 6)))
(run)
; a multislot too short: the test before it still runs, once
(defrule c (t (y ?y&:(p ?y)) (n $? ?z $?)) => (printout t "c " ?z crlf))
(defrule d (t (y ?y&:(p ?y)) (n $? ?z ?w $?)) => (printout t "d " ?z ?w crlf))
(assert (t (y 3) (n)))
(assert (t (y 4) (n 1)))
(run)
; errors before the choices: one report naming every rule through the node
(defrule e (t (y ?y&:(> ?y 0)) (n $? ?z $?)) => (printout t "e " ?z crlf))
(defrule f (t (y ?y&:(> ?y 0)) (n $? ?z ?w $?)) => (printout t "f " ?z ?w crlf))
(defrule g (t (n $? ?z $?) (y ?y&:(> ?y 0))) => (printout t "g " ?z crlf))
(assert (t (y abc) (n 1 2)))
(assert (t (y abc) (n)))
(run)
; an error between the choices: per choice above it
(defrule h (t (m $?a ?b&:(> ?b 0) $?c)) => (printout t "h " ?b crlf))
(assert (t (m 1 x 2)))
(run)
(clear)
; patterns sharing the test before their choices: it runs once for them all
(deftemplate t (slot x) (multislot m))
(deffunction p (?v) (printout t "test " ?v crlf) TRUE)
(defrule a (t (x ?x&:(p ?x)) (m $?a ?b $?c)) => (printout t "a " ?a ?b ?c crlf))
(defrule b (t (x ?x&:(p ?x)) (m $?a ?b ?c $?d)) => (printout t "b " ?a ?b ?c ?d crlf))
(assert (t (x 1) (m 1 2 3)))
(run)
(defrule c (t (x ?x&:(p ?x)) (m $?a ?b&:(p ?b) $?c)) => (printout t "c " ?a ?b ?c crlf))
(assert (t (x 2) (m 4 5)))
(run)
(exit)
