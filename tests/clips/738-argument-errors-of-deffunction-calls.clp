; a run-time error in a builtin call among a deffunction call's arguments is reported
; at once, then CLIPS's [PRCCODE6] naming the deffunction (also under a rule); a
; deffunction that halts in a builtin's argument gives it FALSE, and the builtin reports
; that argument and gives its partial value
(deffunction outer (?y) (printout t "outer " ?y crlf) ?y)
(outer (+ 1 (nth$ 1 (create$ a))))
(outer (str-length (nth$ 1 (create$ 1))) 2)
(deffunction mid () (outer (sqrt (nth$ 1 (create$ x)))) (printout t "not here" crlf))
(mid)
(deffunction bad (?x) (+ ?x (nth$ 1 (create$ a))))
(outer (bad 4))
(printout t "a" (bad 4) "b" crlf)
(str-cat x (bad 4) y)
(+ 1 (bad 4))
(+ 1 (bad 4) 5)
(* 2 3 (bad 4))
(outer (+ 1 (bad 4)))
(create$ a (bad 4) b)
(defrule r0 => (printout t (+ 1 (bad 2)) crlf) (printout t after crlf))
(defrule r => (outer (abs (nth$ 1 (create$ a)))) (printout t after crlf))
(run)
(exit)
