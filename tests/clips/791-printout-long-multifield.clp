; printout of a value longer than 1 KiB prints it whole, as CLIPS does: a solution path
; of an 8-puzzle search (MauroDanielPenaloza/puzzle-clips) printed as one multifield was
; cut after 1 KiB; strings, symbols and floats, before and after other arguments
(deffacts start (camino))
(defrule grow
   ?f <- (camino $?s&:(< (length$ $?s) 240))
   =>
   (retract ?f)
   (assert (camino "izquierda" arriba 1.5 $?s)))
(defrule show
   (camino $?s&:(>= (length$ $?s) 240))
   =>
   (printout t "solucion: " ?s crlf)
   (printout t "a" ?s "b" ?s "c" crlf)
   (printout t (length$ ?s) crlf))
(reset)
(run)
(exit)
