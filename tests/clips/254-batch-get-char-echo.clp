(bind ?c (get-char))
xyz
?c
(get-char)
(printout t "after" crlf)
(bind ?d (get-char))

?d
(bind ?l (readline))
a line read whole
?l
(system "echo" " hi")
(exit)
