; expect: 8:22 expected slot
; keeps: robot r1
; keeps: ok
; keeps: For a total of 1 defrule.
; lacks: bad
(deftemplate robot (slot name) (slot pos))
(defrule ok (robot (name ?n)) => (printout t "robot " ?n crlf))
(defrule bad (robot (nme ?n)) => (printout t ?n crlf))
(assert (robot (name r1)))
(run)
(list-defrules)
(exit)
