; Join keys read from elements of a multislot or ordered fact at fixed offsets
; (the host reads them in place): rules sharing a prefix whose next patterns key
; on different elements of the same multislot (each its own index of the shared
; memory), on an element and a plain slot together, and ordered facts keyed on
; their second and third fields; facts asserted before and after the rules'
; memories fill, and retracted.
(deftemplate goal (slot action) (multislot arguments))
(deftemplate thing (slot name) (slot location))
(defrule by-first
  (goal (action move) (arguments ?name ?place))
  (thing (name ?name))
  =>
  (printout t "by-first " ?name " " ?place crlf))
(defrule by-second
  (goal (action move) (arguments ?name ?place))
  (thing (location ?place))
  =>
  (printout t "by-second " ?name " " ?place crlf))
(defrule by-both
  (goal (action move) (arguments ?name ?place))
  (thing (name ?name) (location ?place))
  =>
  (printout t "by-both " ?name " " ?place crlf))
(defrule ordered-second
  (at ?who ?where ?when)
  (thing (location ?where) (name ?n))
  =>
  (printout t "ordered-second " ?who " " ?n crlf))
(defrule ordered-third
  (at ?who ?where ?when)
  (thing (location ?when) (name ?n))
  =>
  (printout t "ordered-third " ?who " " ?n crlf))
(deffacts f
  (thing (name ladder) (location t1))
  (thing (name chest) (location t2))
  (goal (action move) (arguments ladder t2))
  (goal (action move) (arguments chest t1))
  (at monkey t1 t2))
(reset)
(watch rules)
(run)
(assert (thing (name box) (location t2)))
(assert (goal (action move) (arguments box t1)))
(assert (goal (action move) (arguments box t2)))
(assert (at robot t2 t3))
(assert (thing (name ladder) (location t3)))
(run)
(do-for-all-facts ((?f thing)) (eq ?f:location t2) (retract ?f))
(assert (thing (name chest) (location t2)))
(run)
(facts)
(exit)
