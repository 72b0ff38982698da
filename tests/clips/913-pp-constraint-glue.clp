; pretty-printing glues a `=` or `:` to the call after it in a pattern, a
; deffacts fact and the facts of assert, modify and duplicate, however it was
; written; among a call's arguments it keeps the space
(watch facts)
(watch rules)
(deftemplate t (slot a) (multislot b))
(defrule r1
   (t (a ?x&: (> ?x 1)) (b $? = (+ ?x 1) $?))
   (t (a ?y& : (> ?y 1)) (b ?z&= (+ 1 2)|: (< ?z 0)))
   (foo : (> 1 0))
   (test (= (+ 1 2) 3))
   (not (bar ?w&: (eq ?w ?x)))
   =>
   (printout t = (+ 1 2) : (+ 3 4) crlf)
   (assert (t (a = (+ 1 2)) (b x = (+ 1 2) y)))
   (assert (foo = (+ 1 2) bar))
   (if (> 1 0) then (assert (foo = (* 2 3)))))
(ppdefrule r1)
(defrule r2 ?f <- (t (a ?x)) => (modify ?f (a = (+ ?x 1))) (duplicate ?f (b = (create$ 1 2))))
(ppdefrule r2)
(deffunction f () (printout t = (+ 1 2) crlf) (assert (foo = (+ 1 2))))
(ppdeffunction f)
(deffacts d (foo = (+ 1 2)) (t (a = (+ 1 2))))
(ppdeffacts d)
(exit)
