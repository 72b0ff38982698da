; [PRCCODE3] (a variable nothing binds, read in actions) is reported once the
; construct is read whole: another error after the variable (an unknown
; function, a bind without a variable, a single-field slot given twice) is
; reported instead, with the construct shown up to it; alone it shows the
; construct whole. Nothing of them is kept.
(deftemplate t (slot a))
(deffunction f (?a) (+ ?a ?b) (foo))
(deffunction f2 (?a) (printout t ?b crlf) (bind))
(deffunction f3 (?a) (printout t ?b crlf) (assert (t (a 1 2))))
(deffunction f4 (?a) (printout t ?b crlf) ?a)
(defrule r (a) => (printout t ?q) (bind))
(defrule r2 (a) => (printout t ?q) (foo 1))
(defrule r3 (a ?x) => (printout t ?q ?x crlf) (assert (t (a ?x ?x))))
(defrule r4 (or (a ?x) (b ?y)) => (printout t ?x crlf))
(defrule r5 (a ?x) => (if (> ?x 1) then (printout t ?z crlf) else (foo)))
(defrule r6 (a ?x) => (printout t ?q crlf))
(defrule good (a ?x) => (printout t "good " ?x crlf))
(list-defrules)
(list-deffunctions)
(assert (a 1))
(run)
(exit)
