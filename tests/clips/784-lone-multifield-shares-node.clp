; A multislot constrained only by one multifield (`$?x` or `$?`) and no test of the
; pattern's own matches every value, like a slot the pattern leaves out: CLIPS 6.30
; makes no pattern node for it, so the pattern shares its node and its first join with
; patterns that do not name the slot, and activations come in that shared order.
(deftemplate box (multislot items) (slot tag) (multislot notes))
(open "lone-rules.clp" lone "w")
(printout lone "(defrule r1 (box (tag ?t)) => (printout t r1 crlf))" crlf)
(printout lone "(defrule r2 (box (tag ?t)) => (printout t r2 crlf))" crlf)
(printout lone "(defrule r3 (a) (box (tag ?t)) => (printout t r3 crlf))" crlf)
(printout lone "(defrule r4 (box (tag ?t)) (a) => (printout t r4 crlf))" crlf)
(printout lone "(defrule r5 (box (items $?p) (tag ?t)) => (printout t r5 \" \" ?p crlf))" crlf)
(printout lone "(defrule r6 (box (items $?p&:(> (length$ ?p) -1)) (tag ?t)) => (printout t r6 crlf))" crlf)
(printout lone "(defrule r7 (box (notes $?) (items $?i) (tag ?t)) (a) => (printout t r7 \" \" ?i crlf))" crlf)
(printout lone "(defrule r8 (box (items $?i) (tag ?t&:(member$ ?t ?i))) => (printout t r8 crlf))" crlf)
(printout lone "(defrule r9 (box (items)) => (printout t r9 crlf))" crlf)
(printout lone "(defrule r10 (box (items ?one)) => (printout t r10 \" \" ?one crlf))" crlf)
(close lone)
(watch compilations)
(load "lone-rules.clp")
(unwatch compilations)
(watch activations)
(assert (a))
(assert (box (items) (tag b0)))
(assert (box (items b1 x) (tag b1) (notes n)))
(assert (box (items q) (tag q)))
(run)
; the case found first: two patterns of one rule on one node, the second with a
; join test on the lengths; a later rule naming only `tag`
(clear)
(deftemplate box (multislot items) (slot tag))
(defrule jl
  (box (items $?p) (tag ?s))
  (box (items $?q&:(> (length$ ?q) (length$ $?p))) (tag ?t))
  =>
  (printout t "jl " ?s " " ?t crlf))
(defrule js
  (box (tag ?t))
  (name ?s)
  (test (< 1 2))
  =>
  (printout t "js " ?t crlf))
(watch activations)
(assert (box (items) (tag b0)))
(assert (name "ab"))
(assert (box (items z) (tag bad)))
(modify 3 (items z y))
(run)
(exit)
