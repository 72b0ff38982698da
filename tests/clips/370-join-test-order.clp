; Join tests whose and-members are taken in another order on the host (equalities
; before ~ tests): the same matches, activation order and error reports, with a
; numeric test (which can report an error on a symbol) between them, float and
; ordered-fact operands.
(deftemplate cell (slot id) (slot v) (slot tag))
(deftemplate pick (slot a) (slot b) (slot x))
(deffacts start
  (triple 1 2 3)
  (cell (id 1) (v 1) (tag p))
  (cell (id 2) (v 4) (tag q))
  (cell (id 3) (v 5) (tag p))
  (cell (id 4) (v 2) (tag r))
  (cell (id 5) (v 7) (tag q))
  (cell (id 6) (v abc) (tag p))
  (cell (id 7) (v 3.0) (tag r))
  (pick (a 2) (b 5) (x 3))
  (pick (a 6) (b 3) (x 0)))
(defrule ordered-and-or
  (triple ?v1 ?v2 ?v3)
  (pick (a ?i1) (b ?i2))
  (cell (v ?v&~?v1&~?v2&~?v3) (id ?id&?i1|?i2))
  =>
  (printout t "ordered-and-or " ?id " " ?v crlf))
(defrule neq-then-eq
  (pick (a ?a) (x ?x))
  (cell (id ?id&~?x&?a) (tag ?t&~r))
  =>
  (printout t "neq-then-eq " ?id " " ?t crlf))
(defrule numeric-between
  (pick (a ?a) (b ?b))
  (cell (id ?id) (v ?v) (tag ?t))
  (test (and (neq ?t r) (> ?v 1) (eq ?id ?a)))
  =>
  (printout t "numeric-between " ?id " " ?v crlf))
(defrule not-of-eq
  (pick (a ?a) (b ?b))
  (cell (id ?id&~?b) (tag ?t))
  (test (and (not (eq ?t q)) (or (eq ?id ?a) (eq ?id 1))))
  =>
  (printout t "not-of-eq " ?id " " ?t crlf))
(reset)
(watch rules)
(run)
(facts)
(exit)
