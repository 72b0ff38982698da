; Sorting by swaps on lists long enough for many segmentations per fact, with rule
; firings watched: which swap fires first follows the order of the segmentation
; matches (the longer leading multifield first) and of the facts.
(deffacts d
  (vec a 9 4 7 1 8 2 6 3 5 0)
  (vec b 3.5 1 2.5 2 1.5))
(defrule sort ?h <- (vec ?n $?p ?x $?m ?y&:(> ?x ?y) $?f)
  => (retract ?h) (assert (vec ?n $?p ?y $?m ?x $?f)))
(defrule sorted (declare (salience -5)) (vec ?n $?all)
  (not (vec ?n $? ?x $? ?y&:(< ?y ?x) $?))
  => (printout t ?n " sorted " $?all crlf))
(watch rules)
(reset)
(run)
(exit)
