; Segmentations of patterns over two multislots, the pattern naming the slots in
; another order than the template, alone and beside other patterns of the template:
; the activations' order (CLIPS tries longer multifields first, slot by slot).
(deftemplate t (multislot a) (multislot b))
(watch activations)
(defrule s1 (t (b $?b1 ?y $?b2) (a $?a1 ?x $?a2)) => (printout t "s1 " ?x " " ?y crlf))
(assert (t (a 1 2 3) (b x y)))
(defrule s2 (t (a $?a1 ?x $?a2) (b $?b1 ?y&:(neq ?y z) $?b2)) => (printout t "s2 " ?x " " ?y crlf))
(defrule s3 (t (a $? ?x $?) (b $?)) => (printout t "s3 " ?x crlf))
(assert (t (a 4 5) (b y z w)))
(assert (t (a) (b q)))
(run)
(exit)
