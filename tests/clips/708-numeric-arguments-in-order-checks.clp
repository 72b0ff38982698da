; A numeric call whose arguments are taken in order (a later one could print or change
; something, see 743 and 704) keeps what its builtin's row says as it is read: its return
; type for the call around it, its argument types for the rule's variables
; ([RULECSTR3]), its place in `get-function-list` and `get-function-restrictions`; and
; a recursion through such calls nests as deep as before.
(defglobal ?*s* = a ?*n* = 4)
(deffunction side (?tag) (printout t "side " ?tag crlf) 1)
(+ 1 (= ?*s* (side eq)))
(+ 1 (< ?*n* (side lt)))
(printout t (+ 1 (- ?*n* (side minus))) crlf)
(printout t (str-cat (* ?*n* (side times))) crlf)
(deftemplate v (slot x (type SYMBOL)))
(defrule bad (v (x ?x)) => (printout t (+ ?x (side bad)) crlf))
(defrule ok (v (x ?x&:(< ?*n* (side lhs)))) => (printout t "ok " ?x crlf))
(assert (v (x q)))
(run)
(numberp (member$ + (get-function-list)))
(get-function-restrictions +)
(get-function-restrictions <)
(deffunction w (?a) (while (< ?a (side loop)) do (bind ?a (+ ?a (side inc)))) ?a)
(w -1)
(deffunction fact (?n) (if (<= ?n 1) then 1 else (* ?n (fact (- ?n 1)))))
(fact 10)
(exit)
