(while ?a do)
(while ?a do (printout t "never" crlf))
(assert (j ?u))
(assert (k x ?u y))
(facts)
(printout t "a" ?q "b" crlf)
(if ?zz then (printout t yes crlf) else (printout t no crlf))
(loop-for-count (?i 1 ?n) (printout t ?i crlf))
(switch ?q (case 1 then 1))
(progn$ (?v ?m) 1)
(bind ?y 3)
(bind ?y)
?y
?never-bound
(bind ?a TRUE)
(bind ?c 0)
(while ?a do (bind ?c (+ ?c 1)) (if (> ?c 2) then (bind ?a FALSE)))
?c
(exit)
