; batch* forgets the variables a top-level bind set once each of its commands ran
; (those bound at the prompt before it too); batch and the prompt keep them
(open "b1.clp" f "w")
(printout f "(bind ?x 5)" crlf)
(printout f "(printout t \"x=\" ?x crlf)" crlf)
(printout f "(bind ?y 7)" crlf)
(printout f "?y" crlf)
(printout f "(bind ?m (create$ a b c))" crlf)
(printout f "(printout t \"m=\" ?m crlf)" crlf)
(close f)
(open "b2.clp" f "w")
(printout f "(printout t \"z=\" ?z crlf)" crlf)
(printout f "(bind ?z 9)" crlf)
(printout f "(progn (bind ?w 1) (printout t \"w=\" ?w crlf))" crlf)
(printout f "(printout t \"z2=\" ?z crlf)" crlf)
(close f)
(open "b3.clp" f "w")
(printout f "; only a comment" crlf)
(close f)
(batch* "b1.clp")
?x
?y
(batch "b1.clp")
?x
?m
(bind ?z 1)
(batch* "b2.clp")
?z
(bind ?k 4)
(batch* "b3.clp")
?k
(defglobal ?*g* = 3)
(open "b4.clp" f "w")
(printout f "(bind ?*g* 8)" crlf)
(printout f "(printout t \"g=\" ?*g* crlf)" crlf)
(close f)
(batch* "b4.clp")
?*g*
(exit)
