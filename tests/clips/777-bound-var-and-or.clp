; A variable leading a field and followed by `&` is a constraint of its own, also when
; an earlier pattern (or slot) bound it: CLIPS reads `?z&2|3` as `?z&(2|3)`, not by
; precedence as `(?z&2)|3`, which would let (a (x 3)) match whatever ?z holds.
(deftemplate a (slot x) (slot y) (multislot m))
(deftemplate b (slot x))
(deffacts start
   (b (x 1)) (b (x 3))
   (a (x 3) (y 3) (m 3 1)) (a (x 1) (y 2) (m 2)) (a (x 2) (y 1) (m 1 3)))
(defrule pos (b (x ?z)) (a (x ?z&2|3)) => (printout t "pos " ?z crlf))
(defrule pos-rev (b (x ?z)) (a (x ?z&3|2)) => (printout t "pos-rev " ?z crlf))
(defrule neg (b (x ?z)) (not (a (x ?z&2|3))) => (printout t "neg " ?z crlf))
(defrule ex (b (x ?z)) (exists (a (x ?z&1|2))) => (printout t "ex " ?z crlf))
(defrule and-or (b (x ?z)) (a (x ?z&~2&1|3) (y ?y)) => (printout t "and-or " ?z " " ?y crlf))
(defrule test-or (b (x ?z)) (a (x ?z&:(> ?z 2)|1)) => (printout t "test-or " ?z crlf))
(defrule same-pattern (a (x ?v) (y ?v&1|3)) => (printout t "same-pattern " ?v crlf))
(defrule elem (b (x ?z)) (a (m ?z&2|3 $?)) => (printout t "elem " ?z crlf))
(defrule bar-first (b (x ?z)) (a (x ?z|2) (y ?y)) => (printout t "bar-first " ?z " " ?y crlf))
(defrule unbound (a (x ?w&2|3) (y ?y)) => (printout t "unbound " ?w " " ?y crlf))
(defrule again (b (x ?y&1|3)) (b (x ?y&1|3)) (exists (b (x ?y&1|3))) => (printout t "again " ?y crlf))
(reset)
(agenda)
(run)
(exit)
