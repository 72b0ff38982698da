; a reset in a rule's actions: the rule's variables still hold what they matched
(deftemplate m (slot max) (multislot tags))
(deffacts d (m (max 0)) (a x) (b y))
(deffunction show (?d $?t)
  (printout t "show " ?d " " $?t crlf))
(defrule again
  ?f <- (m (max ?d&~0) (tags $?t))
  =>
  (reset)
  (assert (zz 1 2 3 4))
  (printout t "after reset ?d = " ?d " tags " $?t crlf)
  (show ?d $?t)
  (assert (resetted ?d $?t)))
(defrule seen
  (resetted ?d $?t)
  =>
  (printout t "seen " ?d " " $?t crlf))
(reset)
(do-for-fact ((?f m)) TRUE (modify ?f (max 1) (tags p q)))
(run)
(facts)
(assert (m (max 7) (tags r)))
(run 1)
(facts)
(exit)
