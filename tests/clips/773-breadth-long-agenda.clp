; the breadth strategy with over ten thousand activations of one salience:
; each new activation goes last (the run must not take time growing with the
; agenda's length for each one)
(deftemplate node (slot depth) (slot id))
(deffacts root (node (depth 0) (id 0)))
(defglobal ?*made* = 0)
(defrule expand
  (node (depth ?d&:(< ?d 30)) (id ?i))
  =>
  (bind ?*made* (+ ?*made* 1))
  (assert (node (depth (+ ?d 1)) (id (* ?i 2))))
  (assert (node (depth (+ ?d 1)) (id (+ (* ?i 2) 1)))))
(defrule deep
  (declare (salience 10))
  (node (depth 12) (id ?i&:(= (mod ?i 1000) 0)))
  =>
  (printout t "depth 12 reached by node " ?i crlf))
(set-strategy breadth)
(reset)
(run 12000)
?*made*
(length$ (get-fact-list))
(set-strategy depth)
(reset)
(run 12000)
?*made*
(exit)
