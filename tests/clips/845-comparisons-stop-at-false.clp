; comparisons of three or more arguments evaluate each argument in its turn: the
; first pair that fails ends the call (FALSE), later arguments never run; a number
; argument of another type is [ARGACCES5]; a failing argument goes on with its
; value after the error; `!=` (CLIPS 6.30's older `<>`) after an unbound global or
; a failing call reports its argument as `<>` does
(defglobal ?*g* = 0)
(deffunction bump () (bind ?*g* (+ ?*g* 1)))
(< 2 1 (bump))
?*g*
(< 1 2 (bump))
?*g*
(= 1 1 (bump) (bump))
?*g*
(<> 5 5 (bump))
?*g*
(<> 5 6 (bump))
?*g*
(eq a b (bump))
?*g*
(eq a a (bump))
?*g*
(neq a a (bump))
?*g*
(neq a b (bump) (bump))
?*g*
(>= 3 3 (bump) 0)
?*g*
(> 3 2 1 ?*u*)
(> 3 2 2 ?*u*)
(< 1 2 (+ 1 (/ 4 0)) 9)
(< 1 2 (+ 1 (/ 4 0)) 0)
(< 1 (+ 1 (/ 4 0)) (bump))
?*g*
(bind ?s abc)
(< 1 ?s (bump))
?*g*
(+ 1 (< 1 ?s 3))
(+ 1 (< 1 2 (+ 1 (/ 4 0))))
(eq 1 1.0 (bump))
(eq (create$ a b) (create$ a b) (create$ a b))
(neq 1 1.0 1)
(= 1 1.0 1)
(< 1 1.5 2)
(deffunction bad () (+ 1 (nth$ 5 (create$ a))))
(< 1 (bad) 9)
(< 1 9 (bad))
(< 9 1 (bad))
(deftemplate t (slot x))
(defrule r (t (x ?x&:(< 0 ?x 10))) => (printout t ?x crlf))
(defrule s (t (x ?x)) (test (>= 10 ?x (bump))) => (printout t s ?x crlf))
(assert (t (x 5)) (t (x 11)) (t (x 0)))
(run)
?*g*
(if (< 1 2 3) then (printout t yes crlf))
(funcall < 1 3 2)
(!= ?*u* 4)
(!= (+ 1 (/ 4 0)) 4)
(!= ?s 4)
(!= 4 ?*u*)
(!= 4 (+ 1 (/ 4 0)))
(!= 4 ?s)
(exit)
