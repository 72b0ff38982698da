; load of constructs with errors: "Defining ..." (or the progress mark) is printed once
; the name is read, so the error follows it; a static default that fails to evaluate
; shows its error and the deftemplate up to the attribute; a slot pattern of a
; template that does not exist shows the rule up to the "(" where CLIPS stopped
(watch facts)
(deffunction write-file (?name $?lines)
   (open ?name out "w")
   (progn$ (?l ?lines) (printout out ?l crlf))
   (close out))
(write-file "c.clp"
   "(deffunction boom () (printout t \"boom ran\" crlf) (+ 1 (nth$ 1 (create$ a))))"
   "(deftemplate good (slot a (default 1)))"
   "(deftemplate t1 \"with a comment\" (slot a (default (div 1 0))))"
   "(deftemplate t2 (multislot a (type INTEGER) (default 1 (div 1 0) 3)) (slot b))"
   "(deftemplate t3 (slot x) (slot y (type INTEGER) (default (boom))) (slot z))"
   "(defrule r1 \"c\" (t9 (a 1)) => (printout t x))"
   "(defrule r2 ?f <- (t9 (a 1)) => (printout t x))"
   "(defrule r3 (declare (salience 5)) (t9 x (a 1)) => (printout t x))"
   "(defrule r4 (good (a ?x)) (not (t9 (a ?x))) => (printout t x))"
   "(defrule r5 (good (a ?x)) (t9 ?x (a)) => (printout t x))"
   "(defrule ok (good (a ?x)) (t9 ?x) => (printout t ok crlf))"
   "(defrule ok (good (a ?x)) => (printout t ok crlf))"
   "(deffacts f (good (a 2)))")
(load c.clp)
(list-deftemplates)
(list-defrules)
(unwatch compilations)
(clear)
(load c.clp)
(watch compilations)
(clear)
(batch c.clp)
(list-deftemplates)
(exit)
