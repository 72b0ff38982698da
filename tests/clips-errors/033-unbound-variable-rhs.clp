; expect: 9:43 expected bound
; keeps: ok 1
; keeps: ok
; keeps: For a total of 1 defrule.
; lacks: bad
(deftemplate good (slot a))
(deffacts start (good (a 1)))
(defrule ok (good (a ?x)) => (printout t "ok " ?x crlf))
(defrule bad (good (a ?x)) => (printout t ?y crlf))
(reset)
(run)
(list-defrules)
(exit)
