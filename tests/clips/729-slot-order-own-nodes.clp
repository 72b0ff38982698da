; CLIPS builds a pattern's nodes in the pattern network in the order the pattern
; names its slots: patterns testing the same fields in another order end at nodes
; of their own, and a fact visits the two paths apart (newest first), so the
; activations of their rules come in CLIPS's order. Multifield choices, a selector
; constant, a variable tested against another slot, rules added later (incremental
; reset), a rule redefined, reset with deffacts, and (watch rules).
(deftemplate t (slot x) (slot y) (multislot m) (multislot n))
(defrule a1 (t (x 1) (m $?p ?q $?r)) => (printout t "a1 " ?p ?q ?r crlf))
(defrule a2 (t (m $?p ?q $?r) (x 1)) => (printout t "a2 " ?p ?q ?r crlf))
(defrule a3 (t (x 1) (m $?p ?q $?r)) => (printout t "a3 " ?p ?q ?r crlf))
(defrule b1 (t (y ?y&:(> ?y 0)) (n $? ?z $?)) => (printout t "b1 " ?z crlf))
(defrule b2 (t (n $? ?z $?) (y ?y&:(> ?y 0))) => (printout t "b2 " ?z crlf))
(defrule c1 (t (m ?a $?) (n ?b $?)) => (printout t "c1 " ?a ?b crlf))
(defrule c2 (t (n ?b $?) (m ?a $?)) => (printout t "c2 " ?a ?b crlf))
(defrule d1 (t (x ?x) (m $?p ?x $?)) => (printout t "d1 " ?p crlf))
(defrule d2 (t (m $?p ?x $?) (x ?x)) => (printout t "d2 " ?p crlf))
(watch activations)
(assert (t (x 1) (y 2) (m 1 2 1) (n 3 4)))
(run)
(watch rules)
(assert (t (x 1) (y 3) (m 5 1) (n 6)))
(run)
(agenda)
; rules added later meet the facts (incremental reset), in the order of their paths
(defrule e1 (t (m $?p ?q $?r) (x 1)) => (printout t "e1 " ?p ?q ?r crlf))
(defrule e2 (t (x 1) (m $?p ?q $?r)) => (printout t "e2 " ?p ?q ?r crlf))
(run)
; a rule redefined with its slots in the other order
(defrule a1 (t (m $?p ?q $?r) (x 1)) => (printout t "a1' " ?p ?q ?r crlf))
(assert (t (x 1) (y 0) (m 7 8) (n 9 9)))
(run)
(unwatch all)
(clear)
; without errors, no side effects: the order of the activations only
(deftemplate t (slot x) (multislot m))
(defrule a (t (x ?x&:(> ?x 2)) (m $?a ?b $?c)) => (printout t "a " ?b crlf))
(defrule b (t (m $?a ?b $?c) (x ?x&:(> ?x 2))) => (printout t "b " ?b crlf))
(defrule c (t (x ?x&:(> ?x 2)) (m $?a ?b $?c)) (test (> ?b 1)) => (printout t "c " ?b crlf))
(deffacts f (t (x 4) (m 1 2 3)) (t (x 1) (m 4)) (t (x 5) (m 6 7)))
(reset)
(agenda)
(run)
(exit)
