; The tests before a multislot whose length fails run for their errors and
; effects, as CLIPS runs the nodes before that slot's length test: once, or once
; per multifield choice made above them; also when the pattern's path is longer
; than the levels we keep of it (the failing slot then lies after them all).
; Tests that cannot fail or act (equality, eq, neq) show nothing either way.
(deffunction p (?v) (printout t "test " ?v crlf) TRUE)
; a choice in m, then a test, then n too short: the test runs once per choice
(deftemplate a (slot x) (slot y) (multislot m) (multislot n))
(defrule a (a (m $?a ?b $?c ?d $?e) (y ?y&:(p ?y)) (n ?z $?)) => (printout t "a" crlf))
(assert (a (y 1) (m 1 2 3) (n)))
(run)
; a long path: the error before the choices, n too short after them all
(deftemplate b (slot x) (slot y) (multislot m) (multislot n))
(defrule b (b (y ?y&:(< ?y 3)) (m $?am ?bm&:(< ?bm 3) $?cm ?dm&:(> ?dm 0) $?em) (x ?x&:(> ?x 1)) (n ?bn $?)) => (printout t "b" crlf))
(assert (b (x 1) (m 1 2)))
(assert (b (x 1) (y 1) (m 1 2 3)))
(run)
; the same with an effect: once
(deftemplate c (slot x) (slot y) (multislot m) (multislot n))
(defrule c (c (y ?y&:(p ?y)) (m $?am ?bm&:(< ?bm 3) $?cm ?dm&:(> ?dm 0) $?em) (x 1) (n ?bn $?)) => (printout t "c" crlf))
(assert (c (x 1) (y 5) (m 1 2 2)))
(assert (c (x 1) (y 6) (m 1 2 2) (n 4)))
(run)
; equality and neq only: nothing to see, the fact matches where it fits
(deftemplate d (slot x) (slot y) (multislot m) (multislot n))
(defrule d (d (y ?y&~2&:(neq ?y q)) (m $?a ?b&red $?c) (n ?z $?)) => (printout t "d " ?a ?b ?c ?z crlf))
(assert (d (y 1) (m red red) (n)))
(assert (d (y 1) (m red blue red) (n 7)))
(run)
(exit)
