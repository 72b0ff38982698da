; The not (and ...) rule defined after the facts it tests (order fuzz seed 281,
; reduced): the modify's retract unblocks it before the shared rule loses its
; activation; the assert blocks it again before the shared rule's new activation.
(deftemplate a (multislot m) (slot x (default 0)) (slot y (default 0)))
(watch activations)
(assert (o 2 3) (a (m 2) (y 1)) (o 3 1))
(do-for-fact ((?f a)) (= (nth$ 1 (create$ ?f:y 0)) 1) (duplicate ?f (y 3)))
(defrule r2 (o 3 ?x) (a (y ?z&:(> ?z 1)) (m $?n)) =>)
(defrule r3 (not (and (o 3 ?x) (a (y ?z&:(> ?z 1)) (m $?n)))) =>)
(do-for-fact ((?f a)) (= (nth$ 1 (create$ ?f:y 0)) 3) (modify ?f (y 2)))
(do-for-fact ((?f a)) (= (nth$ 1 (create$ ?f:y 0)) 2) (duplicate ?f (y 2)))
(agenda)
(run 40)
(exit)
