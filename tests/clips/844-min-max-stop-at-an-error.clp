; min and max check each argument before the next runs (CLIPS's ArgTypeCheck): one
; that sets the evaluation error (an unbound global, a failing call, a deffunction
; that halted) stops the call with the best so far (0 for none) and no [ARGACCES5];
; a wrong type stops it with [ARGACCES5]; later arguments never run
(defglobal ?*g* = 0)
(max 4 ?*u* (bind ?*g* 1))
?*g*
(bind ?s abc)
(min 4 ?s (bind ?*g* 2))
?*g*
(max (bind ?*g* 3) ?*u* 9)
?*g*
(defglobal ?*h* = 5)
(deffunction f (?x) (max ?x 2 (+ 1 (/ 4 0)) (bind ?*g* 4)))
(f 7)
?*g*
(deffunction h (?x) (min ?x 2 ?*h*))
(defrule r => (printout t (max 3 (f 1)) crlf) (printout t "after" crlf))
(reset)
(run)
(max 1 (create$ 1 2) (bind ?*g* 6))
?*g*
(min ?*u* 1)
(min (abs ?*u*) 7)
(max 4 (str-cat ?*u*) 9)
(min 4 (+ 1 (/ 4 0)) 9)
(+ 1 (max 4 ?s))
(+ 1 (max 4 ?*u*))
(funcall max 3 8)
(funcall min 3 ?s)
(sort > 3 1 2)
(max 1.5 2 2.0)
(min 1 1.0)
(get-function-restrictions max)
(exit)
