; Join tests with integer arithmetic (+, -, *, mod, nested), from test CEs and
; predicate constraints, over integers, floats and a zero divisor (a symbol
; operand of nested arithmetic prints its errors differently: not here).
(deftemplate n (slot v))
(deftemplate d (slot x))
(defrule div0
  (d (x ?x))
  (n (v ?a&:(> ?a 1)))
  (test (= (mod ?a ?x) 1))
  =>
  (printout t "div0 " ?a " " ?x crlf))
(defrule sum-mod
  (n (v ?a))
  (n (v ?b&:(> ?b ?a)))
  (test (= (mod (+ ?a ?b ?b) 7) (- ?b ?a)))
  =>
  (printout t "sum-mod " ?a " " ?b crlf))
(defrule product
  (n (v ?a))
  (n (v ?b&:(= (* ?a ?b 2) (+ (* 10 ?a) (* 3 ?b)))))
  =>
  (printout t "product " ?a " " ?b crlf))
(defrule by-mod
  (n (v ?a))
  (n (v ?b&~0))
  (test (eq (mod ?a ?b) 1))
  =>
  (printout t "by-mod " ?a " " ?b crlf))
(defrule wide
  (n (v ?a))
  (test (< (* ?a 4611686018427387904) 0))
  =>
  (printout t "wide " ?a crlf))
(defrule nested
  (n (v ?a))
  (n (v ?b))
  (n (v ?c&~?a&~?b))
  (test (= (+ (* 100 ?a) (* 10 ?b) ?c) (- (* 3 (+ ?a ?b ?c)) (mod ?c 2))))
  =>
  (printout t "nested " ?a " " ?b " " ?c crlf))
(watch rules)
(reset)
(assert (n (v 0)) (n (v 1)) (n (v 2)) (n (v 3)) (n (v 5)))
(run)
(assert (n (v 2.5)))
(run)
(assert (n (v -4)) (n (v 7)))
(run)
(assert (d (x 2)))
(run)
(assert (d (x 0)))
(run)
(exit)
