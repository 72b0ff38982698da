; Planned join tests whose operands come from the left token's facts (elements
; of ordered facts, slots, slot plus a constant, arithmetic, an or under an and)
; against many candidates each. Left tokens are retracted and new ones asserted
; between walks (their ids come back with other values), a left value that is a
; float sends some tests to the evaluator in the middle of a walk, and a rule
; reads patterns beyond the first eight.
(deftemplate item (slot id) (slot v) (slot n))
(deftemplate sel (slot a) (slot b) (slot lo))
(deffacts items
  (item (id 1) (v red) (n 1))
  (item (id 2) (v green) (n 2))
  (item (id 3) (v blue) (n 3))
  (item (id 4) (v red) (n 4))
  (item (id 5) (v green) (n 5))
  (item (id 6) (v blue) (n 6))
  (item (id 7) (v black) (n 7))
  (item (id 8) (v white) (n 8))
  (step 0))
(defrule pick-by-elements
  (pair ?x ?y)
  (item (id ?i) (v ?v&~?x&~?y))
  =>
  (printout t "elements " ?x " " ?y " -> " ?i " " ?v crlf))
(defrule pick-either
  (pair ?x ?y)
  (item (id ?i) (v ?x|?y) (n ?n&:(> ?n 2)))
  =>
  (printout t "either " ?x " " ?y " -> " ?i crlf))
(defrule window
  (sel (a ?a) (b ?b) (lo ?lo))
  (item (id ?i) (v ?v&~?a&~?b) (n ?n&:(< ?n (+ ?lo 3))&:(>= ?n ?lo)))
  =>
  (printout t "window " ?a " " ?b " " ?lo " -> " ?i crlf))
(defrule arith
  (sel (a ?a) (lo ?lo))
  (item (id ?i) (n ?n&:(= (mod (+ ?n ?lo) 3) 0)) (v ~?a))
  =>
  (printout t "arith " ?lo " -> " ?i crlf))
(defrule next-step
  (declare (salience -10))
  ?s <- (step ?k&:(< ?k 4))
  =>
  (retract ?s)
  (do-for-all-facts ((?f sel)) TRUE (retract ?f))
  (do-for-all-facts ((?f pair)) TRUE (retract ?f))
  (if (= ?k 2)
   then (assert (sel (a blue) (b red) (lo 2.5)))
   else (assert (sel (a (nth$ (+ ?k 1) (create$ red green blue white)))
                     (b (nth$ (+ ?k 2) (create$ red green blue white black)))
                     (lo (+ ?k 1)))))
  (assert (pair (nth$ (+ ?k 1) (create$ green blue red black))
                (nth$ (+ ?k 1) (create$ white red green blue))))
  (assert (step (+ ?k 1))))
(defrule deep
  (step 4)
  (item (id 1) (v ?v1))
  (item (id 2) (v ?v2))
  (item (id 3) (v ?v3))
  (item (id 4) (v ?v4))
  (item (id 5) (v ?v5))
  (item (id 6) (v ?v6))
  (item (id 7) (v ?v7))
  (item (id 8) (v ?v8))
  (item (id ?i) (v ?v&~?v2&~?v8) (n ?n&:(> ?n 1)&:(< ?n 8)))
  =>
  (printout t "deep " ?v1 " " ?v8 " -> " ?i " " ?v crlf))
(reset)
(run)
(assert (pair red red) (sel (a black) (b white) (lo 5)))
(run)
(exit)
