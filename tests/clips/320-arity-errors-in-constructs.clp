; a call with the wrong number of arguments inside a construct: [ARGACCES4], then the
; construct after ERROR: up to the call's closing parenthesis (rule conditions and
; actions, test CEs, predicate constraints, deffunctions and their control forms,
; deftemplate defaults, deffacts); nothing is defined
(defrule ra (a) => (printout t (sqrt 1 2)))
(defrule rb (a ?x) (test (> ?x)) => (printout t x))
(defrule rc (a ?x&:(> ?x)) => (printout t x))
(defrule rd => (assert (b (+ 1))))
(defrule re (a ?x) => (if (eq ?x 1) then (printout t (str-length)) else (abs 1 2)))
(deffunction fa (?x) (if (> ?x) then (abs)))
(deffunction fb (?x) (while (> ?x 1) do (bind ?x (- ?x))))
(deffunction fc (?x) (switch ?x (case 1 then (nth$ 1)) (default 0)))
(deftemplate tq (slot a (default (+ 1))))
(deftemplate tr (slot a) (multislot b (default-dynamic (create$ (sub-string 1 2)))))
(deffacts dq (a (+ 1)))
(list-defrules)
(list-deffunctions)
(list-deffacts)
(exit)
