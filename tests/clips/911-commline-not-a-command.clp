; at the prompt a command is a `(`, a constant or a variable: a `)`, `&`, `|`,
; `~`, a lone `?` or `$?` is [COMMLINE1] (no blank line before it); the rest of
; the line goes with it, as after any command
(watch facts)
(watch rules)
(printout t "a" crlf))
)
  ) )
&
|
~
?
$?
)(printout t "dropped" crlf)
(printout t "b" crlf)
=>
<-
x
(exit)
