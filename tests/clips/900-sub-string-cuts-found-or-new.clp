; sub-string cuts that exist already as symbols or strings and ones that are new:
; a cut is a string whatever its source, and equal cuts are eq
(defglobal ?*n* = 0)
(deffacts start (s "kalosu" kalo) (s "kami" [kaXY]) (s "" ka))
(defrule cut
  (s ?a ?b)
  =>
  (printout t (sub-string 1 4 ?a) " " (sub-string 1 2 ?b) " "
     (eq (sub-string 1 2 ?a) (sub-string 1 2 ?b)) " "
     (eq (sub-string 1 2 ?b) ka) " " (eq (sub-string 1 2 ?b) "ka") " "
     (stringp (sub-string 1 4 ?b)) " [" (sub-string 3 2 ?a) "] ["
     (sub-string 5 9 ?b) "]" crlf))
(defrule pairs
  (s ?a ?)
  (s ?c&~?a&:(eq (sub-string 1 2 ?a) (sub-string 1 2 ?c)) ?)
  =>
  (bind ?*n* (+ ?*n* 1)))
(reset)
(run)
?*n*
(sub-string 1 3 "abcdef")
(sub-string 1 3 "abcdef")
(sub-string 2 2 [x])
(sub-string 0 1 abc)
(sub-string 1 2 "x\u00e4y")
(exit)
