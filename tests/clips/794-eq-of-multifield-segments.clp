; eq and neq of multifield variables bound between single fields ((r ?h $?m ?t)), the
; join's own pattern against a left one and one left pattern against another, with
; modify changing a segment's length, and a slot of two multifields (each variable's
; bounds set by the match): the same length and each field the same
(deftemplate r (slot id) (multislot v))
(defrule mid-same
   (r (id ?i) (v ?h $?m ?t))
   (r (id ?j&:(> ?j ?i)) (v $?n z))
   (test (eq $?m $?n))
   =>
   (printout t "mid-same " ?i " " ?j " " (length$ $?m) crlf))
(defrule mid-differ
   (r (id ?i) (v ?h $?m ?t))
   (r (id ?j&:(> ?j ?i)) (v $?n z))
   (test (neq $?n $?m))
   =>
   (printout t "mid-differ " ?i " " ?j crlf))
(defrule ordered-tail
   (k ?a $?x)
   (r (id ?i))
   (l $?y ?b ?c)
   (test (and (eq $?x $?y) (neq ?a ?b)))
   =>
   (printout t "ordered-tail " ?a " " ?i " " ?b " " ?c crlf))
(defrule two-multis
   (k ?a $?x)
   (l $?p $?q)
   (test (eq $?x $?q))
   =>
   (printout t "two-multis " ?a " " (length$ $?p) crlf))
(defrule grow
   (declare (salience -10))
   ?f <- (r (id 2) (v $?all))
   (test (< (length$ $?all) 4))
   =>
   (modify ?f (v q $?all z)))
(deffacts d
   (r (id 1) (v a b c d))
   (r (id 2) (v b c z))
   (r (id 3) (v x b c y))
   (r (id 4) (v z))
   (r (id 5) (v x y))
   (r (id 6) (v "b" c z))
   (r (id 7) (v b c 1 z))
   (k 1 b c)
   (k 2)
   (k 3 1.0)
   (l b c 5 6)
   (l 1 1 7)
   (l 8 9))
(reset)
(run)
(exit)
