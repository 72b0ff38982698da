; expect: 8:26 expected constraint
; keeps: ok 5
; keeps: ok
; keeps: For a total of 1 defrule.
; lacks: bad
(deftemplate good (slot a))
(defrule ok (good (a ?x)) => (printout t "ok " ?x crlf))
(defrule bad (good (a ?x&)) => )
(assert (good (a 5)))
(run)
(list-defrules)
(exit)
