; Fact-set queries whose test compares the fact's slots with operands that do not
; depend on the fact (arithmetic and mod of locals, globals, constants, rule
; variables and outer query variables' slots), alone or under and: the actions
; change what the operands read (locals, globals), bodies nested, empty or
; retracting, mixed integer and float comparisons, and the errors the operands and
; slots raise (a symbol in arithmetic, mod by zero, a multifield, an unbound variable),
; tuples of two variables retracting the inner one
(deftemplate item (slot id) (slot w) (slot kind) (multislot tags))
(deftemplate link (slot from) (slot to))
(defglobal ?*lim* = 10 ?*n* = 0 ?*s* = 0)
(deffacts items
  (item (id 1) (w 5) (kind 0)) (item (id 2) (w 12) (kind 1)) (item (id 3) (w 7.5) (kind 2))
  (item (id 4) (w 20) (kind 0)) (item (id 5) (w 3) (kind 1) (tags a b)) (item (id 6) (w 12.0) (kind 2))
  (link (from 1) (to 4)) (link (from 2) (to 5)) (link (from 4) (to 6)) (link (from 6) (to 1)))
(reset)
(do-for-all-facts ((?f item)) (> ?f:w (* ?*lim* 1)) (printout t "gt " ?f:id crlf))
(do-for-all-facts ((?f item)) (= ?f:w (+ ?*lim* 2)) (printout t "eqnum " ?f:id crlf))
(do-for-all-facts ((?f item)) (< ?f:w (- ?*lim* 2.5)) (printout t "ltf " ?f:id crlf))
(do-for-all-facts ((?f item)) (eq ?f:w (+ ?*lim* 2)) (printout t "eq " ?f:id crlf))
(do-for-all-facts ((?f item)) (neq ?f:kind (mod ?*lim* 3)) (printout t "neq " ?f:id crlf))
; the actions raise the limit the next facts are compared with
(do-for-all-facts ((?f item)) (>= ?f:w (- ?*lim* 5)) (bind ?*lim* (+ ?*lim* 4)) (printout t "raise " ?f:id " " ?*lim* crlf))
(bind ?*lim* 10)
(deffunction upto (?k)
  (do-for-all-facts ((?f item)) (<= ?f:w (* ?k 2)) (printout t "upto " ?k " " ?f:id crlf) (bind ?k (- ?k 1))))
(upto 6)
(deffunction kinds (?k)
  (find-all-facts ((?f item)) (and (= ?f:kind (mod ?k 3)) (> ?f:w (- ?k 10)))))
(printout t (kinds 3) " " (kinds 4) " " (kinds 14) " " (kinds 20) crlf)
(any-factp ((?f item)) (= ?f:w (* 2.5 3)))
(find-fact ((?f item)) (> ?f:w (+ 1 (* ?*lim* 1.1))))
(find-fact ((?f item)) (< ?f:w (- 0 ?*lim*)))
; nested: the inner test reads the outer fact's slots; bodies empty or retracting
(do-for-all-facts ((?a item)) (= ?a:kind (mod ?*lim* 4))
  (do-for-all-facts ((?b item)) (and (= ?b:kind ?a:kind) (> ?b:w (+ ?a:w 1)))
    (printout t "pair " ?a:id " " ?b:id crlf)))
(do-for-all-facts ((?a item) (?l link)) (and (= ?l:from ?a:id) (> ?a:w (* ?*lim* 0.5)))
  (printout t "link " ?a:id " -> " ?l:to crlf))
(do-for-all-facts ((?a item) (?l link)) (and (= ?l:from ?a:id) (< ?a:w (+ ?*lim* 0))))
(do-for-all-facts ((?a item)) (< ?a:w 10)
  (do-for-all-facts ((?b item)) (and (neq ?b ?a) (= ?b:kind ?a:kind))
    (bind ?*n* (+ ?*n* 1))))
(printout t "n " ?*n* crlf)
(do-for-all-facts ((?l link)) (> ?l:to (+ ?*s* 3)) (bind ?*s* (+ ?*s* ?l:to)) (retract ?l))
(printout t "s " ?*s* " " (find-all-facts ((?l link)) TRUE) crlf)
; the actions assert facts the walk reaches, compared with a limit they move
(do-for-all-facts ((?f item)) (> ?f:w (+ ?*lim* 5)) (bind ?*lim* (+ ?*lim* 32))
  (assert (item (id (+ ?f:id 100)) (w (+ ?f:w 30)) (kind 9))) (printout t "grow " ?f:id crlf))
(find-all-facts ((?f item)) (= ?f:kind (* 3 3)))
; rule variables in the operands
(defrule q
  (go ?k)
  =>
  (printout t "rule " ?k " " (find-all-facts ((?f item)) (and (< ?f:kind (mod ?k 3)) (>= ?f:w (- ?k 1)))) crlf)
  (do-for-all-facts ((?f item)) (= ?f:w (+ ?k 0.0)) (printout t "rule= " ?f:id crlf)))
(assert (go 12) (go 6) (go 5))
(run)
; errors: a symbol in arithmetic, mod by zero, a multifield, an unbound variable
(defglobal ?*sym* = abc ?*zero* = 0)
(do-for-all-facts ((?f item)) (> ?f:w (+ ?*sym* 1)) (printout t "never " ?f:id crlf))
(printout t "after sym" crlf)
(do-for-all-facts ((?f item)) (= ?f:kind (mod 7 ?*zero*)) (printout t "never " ?f:id crlf))
(printout t "after zero" crlf)
(do-for-all-facts ((?f item)) (> ?f:tags (+ 1 1)) (printout t "tags " ?f:id crlf))
(printout t "after tags" crlf)
(do-for-all-facts ((?f item)) (and (> ?f:w 100) (> ?f:tags (+ 1 1))) (printout t "big " ?f:id crlf))
(printout t "after and" crlf)
(do-for-all-facts ((?f item)) (and (< ?f:w 100) (= ?f:kind (mod 7 ?*zero*))) (printout t "never " ?f:id crlf))
(printout t "after and zero" crlf)
(deffunction half (?x) (if (> ?x 5) then (bind ?u 1))
  (do-for-all-facts ((?f item)) (> ?f:w (+ ?u 1)) (printout t "u " ?x " " ?f:id crlf)))
(half 9)
(printout t "after unbound" crlf)
(do-for-all-facts ((?a item) (?b item)) (= ?b:w (+ ?a:w 7)) (printout t "plus7 " ?a:id " " ?b:id crlf))
(do-for-all-facts ((?a item) (?b item)) (and (> ?b:id ?a:id) (= ?b:kind ?a:kind) (< ?b:w (* ?a:w 2)))
  (retract ?b) (printout t "del " ?a:id " " ?b:id crlf))
(do-for-all-facts ((?f item)) (> ?f:w (mod 7.5 2)) (printout t "fmod " ?f:id crlf))
(exit)
