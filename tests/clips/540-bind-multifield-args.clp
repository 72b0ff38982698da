; bind with several values splices each multifield once: LHS multifield variables,
; a function's multifield, a deffunction's wildcard parameter, a global
(defglobal ?*g* = (create$ g1 g2))
(deffunction f ($?y)
  (bind ?b (create$ a b) z)
  (bind ?c $?y z ?y)
  (bind ?d ?*g* $?y)
  (printout t "f: " ?b " " ?c " " ?d crlf))
(defrule r
  (data $?x)
  =>
  (bind ?a $?x)
  (bind ?b $?x z)
  (bind ?c z $?x (create$ 1 2) $?x)
  (bind ?d (create$ a b) z)
  (bind ?e ?*g* $?x)
  (printout t "r: " ?a " " ?b " " ?c " " ?d " " ?e crlf))
(deftemplate state (multislot path))
(defrule extend
  ?s <- (state (path $?p))
  (test (< (length$ $?p) 5))
  =>
  (bind ?q $?p step)
  (modify ?s (path ?q)))
(f p q)
(bind ?top (create$ a b) z (create$))
(printout t ?top crlf)
(assert (data p q))
(assert (state))
(run)
(facts)
(exit)
