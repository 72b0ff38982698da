; A rule's actions that `bind` an LHS variable: CLIPS reads the variable from a
; local everywhere in the actions, also before the `bind` in the text (a loop body
; read again after it), and the LHS value while that local is unbound (before the
; first bind, after `(bind ?x)`). Loop bodies of while, loop-for-count, progn$,
; foreach, if and switch branches, nested loops, a multifield and a fact-address
; variable, a value read from the old binding inside a loop, an `or` rule, and a
; deffunction whose parameter and local are bound in a loop.
(watch rules)
(deffunction f (?r)
   (while (neq ?r 0) do (printout t "f " ?r crlf) (bind ?r 0))
   (loop-for-count (?i 3) (if (= ?i 3) then (printout t "y=" ?y crlf)) (bind ?y ?i))
   done)
(defrule while-mf (w $?r)
   =>
   (while (neq ?r (create$)) do
      (printout t "w=" ?r crlf)
      (bind ?r (rest$ ?r)))
   (printout t "w end " (length$ ?r) crlf))
(defrule count (t ?x)
   =>
   (loop-for-count 2 (printout t "t=" ?x crlf) (bind ?x 0))
   (printout t "after t=" ?x crlf))
(defrule cond (u ?x)
   =>
   (if (> ?x 0) then (bind ?x 0))
   (printout t "u=" ?x crlf))
(defrule old-value (v ?x)
   =>
   (loop-for-count 3 (bind ?x (+ ?x 1)) (printout t "v=" ?x crlf))
   (bind ?x)
   (printout t "v unbound=" ?x crlf))
(defrule fact-var ?f <- (g ?)
   =>
   (progn$ (?e (create$ 1 2)) (printout t "g=" ?f " " ?e crlf) (bind ?f ?e))
   (printout t "g after=" ?f crlf))
(defrule each (h ?a ?b)
   =>
   (foreach ?e (create$ x y z)
      (switch ?e
         (case y then (printout t "h " ?a " " ?b crlf) (bind ?a ?b))
         (default (printout t "h " ?e " " ?a crlf) (bind ?b ?e))))
   (printout t "h end " ?a " " ?b crlf))
(defrule nested (n ?k)
   =>
   (loop-for-count (?i 2)
      (loop-for-count (?j 2)
         (printout t "n " ?i " " ?j " " ?k crlf)
         (bind ?k (+ (* 10 ?i) ?j))))
   (printout t "n end " ?k crlf))
(defrule either (or (o ?x) (p ?x))
   =>
   (while (< ?x 3) do (printout t "o " ?x crlf) (bind ?x (+ ?x 1)))
   (printout t "o end " ?x crlf))
(defrule after-the-loop (q ?x)
   =>
   (printout t "q before=" ?x crlf)
   (loop-for-count 2 (printout t "q=" ?x crlf))
   (bind ?x (create$ ?x ?x))
   (printout t "q after=" ?x crlf))
(f 1)
(assert (w a b c) (t 7) (u 5) (u -5) (v 1) (g 1) (h 1 2) (n 0) (o 1) (p 2) (q 4))
(run)
(exit)
