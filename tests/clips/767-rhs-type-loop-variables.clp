; [RULECSTR3] prints the call with loop variables as CLIPS's replacement calls:
; ((get-loop-count) D), ((get-progn$-field) D), ((get-progn$-index) D), D counting the
; loops of the same kind between the variable's loop and the call (a crossing traffic
; program by others added a fact address to a loop-for-count variable); a
; deffunction call prints as nothing there.
(defrule r1 ?f <- (a) => (loop-for-count (?i 1 2) do (+ ?i ?f)))
(defrule r2 ?f <- (a) => (loop-for-count (?i 1 2) do (loop-for-count (?j 1 2) do (+ ?i ?j ?f))))
(defrule r3 ?f <- (a) => (progn$ (?v (create$ 1)) (+ ?v ?v-index ?f)))
(defrule r4 ?f <- (a) => (foreach ?v (create$ 1) (+ ?v ?f)))
(defrule r5 ?f <- (a) (b ?x) => (bind ?y 2) (+ ?x ?y ?f))
(defrule r6 ?f <- (a) => (loop-for-count 3 do (loop-for-count (?n 2) do (+ ?n ?f))))
(defrule r7 ?f <- (a) => (loop-for-count (?i 1 2) do (progn$ (?v (create$ 1)) (loop-for-count (?k 1 2) do (* ?i ?k ?v ?f)))))
(defrule r8 ?f <- (a) => (loop-for-count (?i 1 2) do (printout t ?i crlf)) (- 5 ?i ?f))
(defrule r9 ?f <- (a) => (progn$ (?x (create$ 1 2)) (foreach ?y (create$ 3) (loop-for-count 2 do (/ ?x-index ?y-index ?y ?f)))))
(deffunction g (?a) (loop-for-count (?i 1 2) do (+ ?i ?a)))
(defrule r10 ?f <- (a) => (loop-for-count (?i 1 2) do (+ (g ?i) ?i ?f)))
(defrule r11 ?f <- (a) => (+ (g 1) ?f))
(defrule r12 ?f <- (a) => (+ 1 (+ (g 1) 2) ?f))
(exit)
