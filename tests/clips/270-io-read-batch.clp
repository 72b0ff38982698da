; read, readline and read-number from stdin in batch mode: they take the batch file's
; next lines (echoed), a read drops the rest of its line, blank and comment lines are
; skipped, and a string ends with its line.
(deffunction kind (?v)
   (if (stringp ?v) then STRING else
   (if (symbolp ?v) then SYMBOL else
   (if (integerp ?v) then INTEGER else
   (if (floatp ?v) then FLOAT else OTHER)))))
(deffunction r () (bind ?v (read)) (printout t (kind ?v) " [" ?v "]" crlf))
(r)
hello world
(r)
?x y
(r)
$?x
(r)
&
(r)
a|b
(r)
~x
(r)
a<b
(r)
=>
(r)
)
(r)
  ; a comment line is skipped


  "esc\"q\\z" x
(r)
-12
(r)
1e3
(r)
+5
(r)
12abc
(r)
3.
(r)
?
(bind ?x (read)) 42 dropped
"a string" more
?x
(readline)
   spaces  kept  
(readline)

(read t)
t-name
(read stdin)
stdin-name
(readline t)
line via t
(read-number)
  12.5 x
(read-number)
abc
(read-number t)
-7
(read)
"unterminated string
(defrule ask
   =>
   (printout t "name? ")
   (bind ?n (read))
   (printout t "got " ?n crlf)
   (printout t "line? ")
   (bind ?l (readline))
   (printout t "L=" ?l crlf)
   (printout t "num? ")
   (bind ?k (read))
   (printout t (kind ?k) " " (* 2 ?k) crlf))
(reset)
(run)
bob smith
another line
3.5e2 x
(read foo)
(readline foo)
(read-number foo)
(read (create$ a))
(read 1)
; a read in a rule's actions takes the next line even when it is a command
(defrule takes-a-command
   =>
   (printout t "read: " (read) crlf))
(run)
(exit)
(exit)
