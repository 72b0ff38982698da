; An `or` of equalities on a field of the joined pattern itself when that pattern
; is an ordered fact (`(rel ?a|?b ?x)`) or a multislot's element at a fixed
; offset: the host indexes the matches on that element and looks up one bucket
; per alternative, keyed (with an equality on another element) and not keyed, in
; a positive join and in a `not`. Same matches and firing order as CLIPS: matches
; interleaved in memory, equal alternatives, an integer against a float, a string
; against a symbol, an element after a multifield (no fixed offset: no lookup),
; a rule made after its facts (its node indexed late), facts retracted and
; asserted while the probes wait, a reset and a second run.
(deftemplate box (multislot m))
(deffacts data
  (rel b 1 x)
  (rel a 1 y)
  (rel c 2 x)
  (rel a 2 z)
  (rel 1 1 w)
  (rel 1.0 2 w)
  (rel "a" 1 s)
  (rel b 2 y)
  (rel a 1 x)
  (box (m a 1))
  (box (m q b 2))
  (box (m b 3)))
(defrule unkeyed
  (want ?p ?q)
  (rel ?p|?q ?n ?t)
  =>
  (printout t "unkeyed " ?p "|" ?q " -> " ?n " " ?t crlf))
(defrule keyed
  (want ?p ?q)
  (num ?n)
  (rel ?p|?q ?n ?t&~?p)
  =>
  (printout t "keyed " ?p "|" ?q " " ?n " -> " ?t crlf))
(defrule none-keyed
  (want ?p ?q)
  (num ?n)
  (not (rel ?p|?q ?n ?))
  =>
  (printout t "none-keyed " ?p "|" ?q " " ?n crlf))
(defrule none-unkeyed
  (want ?p ?q)
  (not (rel ?p|?q ? ?))
  =>
  (printout t "none-unkeyed " ?p "|" ?q crlf))
(defrule box-first
  (want ?p ?q)
  (box (m ?p|?q ?v))
  =>
  (printout t "box-first " ?p "|" ?q " -> " ?v crlf))
(defrule box-after-multi
  (want ?p ?q)
  (box (m $? ?p|?q ?v))
  =>
  (printout t "box-after-multi " ?p "|" ?q " -> " ?v crlf))
(reset)
(assert (num 1) (num 2) (num 3))
(assert (want a b))
(assert (want 1 c))
(assert (want "a" a))
(assert (want zz zz))
(run)
(assert (rel zz 3 v))
(assert (rel c 1 q))
(run)
(retract 3)
(assert (rel b 1 z))
(run)
(defrule late
  (want ?p ?q)
  (num ?n)
  (rel ?n ?p|?q ?)
  =>
  (printout t "late " ?p "|" ?q " " ?n crlf))
(defrule late-unkeyed
  (want ?p ?q)
  (rel ? ? ?p|?q)
  =>
  (printout t "late-unkeyed " ?p "|" ?q crlf))
(assert (rel 2 a k) (rel 1 zz k) (rel 3 b x))
(run)
(reset)
(assert (want b x))
(assert (num 1) (num 2))
(run)
(exit)
