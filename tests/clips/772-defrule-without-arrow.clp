; a defrule that ends before its `=>`, or holds a word where a CE is due: CLIPS
; shows the rule read so far, the `)` or the word on a line of its own
(defrule nothing)
(defrule one-pattern (a))
(defrule commented "no arrow here" (a) (b ?x))
(defrule declared (declare (salience 5)) (a))
(defrule only-declare (declare (salience 5)))
(defrule bound ?f <- (a) (not (b)) (test (> 1 0)))
(defrule a-word (a) word)
(defrule a-number (a) 12 => (assert (x)))
(defrule an-equals (a) (b) =)
(defrule fine (a) => (assert (b)))
(list-defrules)
(exit)
