; `?v:slot` as a later argument of a numeric function: quiet when every template of
; ?v has the slot (the arguments may then be read at once), else read in CLIPS's order
; (a missing slot's [INSFUN3] only when the arguments before it were numbers).
(deftemplate item (slot id) (slot kind) (slot w))
(deftemplate link (slot id) (slot to) (slot w))
(defglobal ?*sum* = 0)
(assert (item (id 1) (kind a) (w 5)) (item (id 2) (kind 7) (w x)))
(assert (link (id 3) (to 2) (w 4)) (link (id 4) (to b) (w 9)))
; one template with both slots: a symbol first ends the arguments
(do-for-all-facts ((?a item)) (eq ?a:id 1) (printout t "a " (= ?a:kind ?a:w) crlf))
(do-for-all-facts ((?a item)) (eq ?a:id 2) (printout t "b " (+ ?a:w ?a:kind) crlf))
(do-for-all-facts ((?a item)) (eq ?a:id 2) (printout t "b2 " (+ ?a:kind ?a:w) crlf))
; two templates, `kind` only in item: its read fails on a link, unless a symbol before it
; ended the arguments
(do-for-all-facts ((?a item link)) (eq ?a:id 4) (printout t "c " (= ?a:to ?a:kind) crlf))
(do-for-all-facts ((?a item link)) (eq ?a:id 3) (printout t "c2 " (= ?a:to ?a:kind) crlf))
(do-for-all-facts ((?a link item)) (eq ?a:id 4) (printout t "d " (- ?a:w ?a:to ?a:kind) crlf))
(do-for-all-facts ((?a link item)) (eq ?a:id 1) (printout t "d2 " (* ?a:kind ?a:to) crlf))
(do-for-all-facts ((?a item link)) (eq ?a:id 3) (printout t "e " (* ?a:w ?a:w) crlf))
; in the condition
(printout t "f " (any-factp ((?a link item)) (> ?a:to ?a:kind)) crlf)
(printout t "f2 " (find-all-facts ((?a item link)) (and (integerp ?a:w) (> ?a:w ?a:to))) crlf)
; an outer variable in an inner query, and an inner one of the same name
(do-for-all-facts ((?a item)) (eq ?a:id 1)
  (do-for-all-facts ((?b link)) (> ?b:w ?a:w)
    (printout t "g " ?a:id " " ?b:id crlf))
  (do-for-all-facts ((?a link)) (> ?a:w 5)
    (printout t "h " ?a:id " " (- ?a:to ?a:w) crlf)))
(do-for-all-facts ((?b link)) (eq ?b:id 4)
  (do-for-all-facts ((?a link item)) (= ?b:to ?a:kind)
    (printout t "i " ?b:id " " ?a:id crlf)))
(do-for-all-facts ((?b link)) (eq ?b:id 3)
  (do-for-all-facts ((?a link item)) (= ?b:to ?a:kind)
    (printout t "j " ?b:id " " ?a:id crlf)))
; sums in the actions, of numbers and then of a symbol
(do-for-all-facts ((?f item link)) (integerp ?f:w) (bind ?*sum* (+ ?*sum* ?f:w)))
(printout t "sum " ?*sum* crlf)
(do-for-all-facts ((?f link item)) TRUE (bind ?*sum* (+ ?*sum* ?f:w)))
(printout t "sum " ?*sum* crlf)
; templates named at run time
(deffunction tally (?t) (bind ?s 0) (do-for-all-facts ((?f ?t)) TRUE (bind ?s (+ ?s ?f:w ?f:to))) ?s)
(printout t "tally " (tally link) crlf)
(printout t "tally " (tally item) crlf)
(exit)
