; eq and neq of two multifield variables, each its pattern's whole multislot, in test CEs
; and predicates (an 8-puzzle search's repeated-state test, MauroDanielPenaloza/puzzle-clips
; sol.clp, compares them for every pair of states): the same length and each field the
; same, an integer never eq its float, a string never eq its symbol, empty lists eq
(deftemplate s (multislot p) (slot n))
(deftemplate o (slot k) (multislot p))
(defrule same
   (s (p $?a) (n ?x))
   (s (p $?b) (n ?y&:(> ?y ?x)))
   (test (eq $?a $?b))
   =>
   (printout t "same " ?x " " ?y crlf))
(defrule differ
   (s (p $?a) (n ?x))
   (s (p $?b) (n ?y&:(> ?y ?x)))
   (test (neq $?a $?b))
   =>
   (printout t "differ " ?x " " ?y crlf))
(defrule same-ordered
   (o (k ?x) (p $?a))
   (q $?b)
   (test (and (eq $?a $?b) (neq ?x 0)))
   =>
   (printout t "ordered " ?x " " ?b crlf))
(defrule same-pred
   (s (p $?a) (n ?x))
   (o (k ?k) (p $?b&:(eq $?a $?b)))
   =>
   (printout t "pred " ?x " " ?k crlf))
(deffacts d
   (s (p a b c) (n 1))
   (s (p a b c) (n 2))
   (s (p a b) (n 3))
   (s (p 1 2) (n 4))
   (s (p 1.0 2) (n 5))
   (s (p 1 2) (n 6))
   (s (p "a" b c) (n 7))
   (s (p) (n 8))
   (s (p) (n 9))
   (o (k 1) (p a b c))
   (o (k 0) (p 1 2))
   (o (k 2) (p))
   (q a b c)
   (q 1 2)
   (q))
(reset)
(run)
(exit)
