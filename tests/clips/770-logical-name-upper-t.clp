; `T` names the same logical name as `t` wherever CLIPS reads one: output to
; the terminal, input from it, and refused by open and close
(watch facts)
(printout T "printout to T" crlf)
(printout "T" "printout to the string T" crlf)
(format T "format to T: %d%n" 42)
(format "T" "%s%n" "format to the string T")
(read T)
word
(readline T)
a whole line
(read-number T)
17
(get-char T)
Q
(open "never-made.txt" T "w")
(open "never-made.txt" "T" "w")
(close T)
(close t)
(close "T")
(assert (point 1 2))
(ppfact 1 T)
(deffunction say (?where) (printout ?where "said to " ?where crlf))
(say T)
(say t)
(say TT)
(defrule shout (point ?x ?y) => (printout T "point " ?x " " ?y crlf))
(run)
(exit)
