; a variable bound to the value of a command that returns nothing (printout, retract,
; run, facts, a deffunction ending in one): bound, not unbound; reading it gives no
; value (printed as nothing, an empty line when typed alone, dropped by create$ and
; bind's multifield, refused by str-cat and type); at the prompt, in deffunctions,
; loops and rule actions; a defglobal holding it
(watch facts)
(watch rules)
(bind ?x (printout t "a" crlf))
?x
(printout t ?x crlf)
(printout t "[" ?x "]" crlf)
(bind ?y (assert (foo 1)))
?y
(bind ?z (retract 1))
?z
(bind ?w (printout t "b"))
(create$ ?w 1 2)
(length$ (create$ ?w))
(type ?x)
(eq ?x nil)
(str-cat ?x "q")
(defglobal ?*g* = (printout t "g" crlf))
?*g*
(deffunction f () (printout t "in f" crlf))
(bind ?v (f))
?v
(printout t (f) crlf)
(bind ?m (create$ 1 (printout t "x" crlf) 2))
?m
(bind ?r (run))
?r
(bind ?s (facts))
?s
(deffunction g () (bind ?q (printout t "gq" crlf)) ?q)
(g)
(deffunction h () (bind ?q (printout t "hq" crlf)) (create$ a ?q b))
(h)
(bind ?m a (printout t "x" crlf) b)
?m
(bind ?n (printout t "y" crlf) (printout t "z" crlf))
?n
(length$ ?n)
(defrule r => (bind ?v (printout t "in r" crlf)) (printout t "[" ?v "]" crlf) (bind ?w (create$ 1 ?v 2)) (printout t ?w crlf))
(reset)
(run)
(defglobal ?*h* = 1)
(bind ?*h* (printout t "h" crlf))
?*h*
(show-defglobals)
(bind ?x (printout t "q" crlf))
(bind ?x)
?x
(deffunction k (?p) (printout t "k:" ?p ":" crlf) (bind ?p (printout t "")) ?p)
(k 1)
(loop-for-count (?i 1 2) (bind ?u (printout t "u" ?i crlf)) (printout t "<" ?u ">" crlf))
(if (bind ?c (printout t "c" crlf)) then (printout t "true" crlf) else (printout t "false" crlf))
(bind ?s (str-cat (printout t "s" crlf)))
?s
(exit)
