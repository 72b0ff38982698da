; A `=` or `:` written glued to the call after it stays glued when printed only as a
; constraint in a pattern or fact (`(b =(+ 1 1))`, `?y&:(> ?y 1)`, an assert's fact,
; a deffacts fact); as a function's name (`(=(+ 1 1) 2)`) or a call's argument it is
; printed with a space after it: ppdefrule, ppdeffunction, ppdefglobal, ppdeffacts,
; ppdeftemplate and the ERROR: echo of a failed defrule
(defrule r1 (a ?x) (test (=(+ ?x 1) 2)) (b =(+ 1 1)) (c ?y&=(+ 1 1)) (d ?z&:(>(+ ?z 1) 2))
   => (printout t =(+ 1 2) crlf) (printout t :(+ 1 2) crlf) (assert (e =(+ 1 1)))
   (bind ?q (create$ =(+ 1 1))))
(ppdefrule r1)
(deffunction f (?x)
   (if (=(mod ?x 2) 0) then (>=(+ 1 1) 2))
   (while (=(+ 1 1) 3) do (bind ?x 1))
   (switch (=(+ 1 1) 2) (case TRUE then (=(+ 2 2) 4))))
(ppdeffunction f)
(defglobal ?*g* = (=(+ 1 1) 2))
(ppdefglobal g)
(deffacts d (e =(+ 1 1)) (f (=(+ 1 1) 2)))
(ppdeffacts d)
(deftemplate t (slot s (default (=(+ 1 1) 2))) (slot u (default-dynamic (=(+ 1 1) 2))))
(ppdeftemplate t)
(defrule r2 => (bind ?v (=(+ 1 1) 2)) (printout t ?unbound crlf))
(exit)
