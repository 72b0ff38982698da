; `run` as the argument of a function: the rules fire inside the call, whose value
; check then refuses the void result (str-cat; create$ drops it); also from a
; deffunction, and `(run)` nested in `progn`. Then `clear` inside a larger command:
; the command goes on with its own arguments (a compiled rule base's constructs read
; in place too), and a rule it builds after the clear does not overwrite them.
(watch facts)
(watch rules)
(deftemplate a (slot x))
(defrule go (a (x ?x)) => (printout t "fired " ?x crlf))
(defrule more (a (x 1)) => (assert (a (x 2))))
(deffunction runner () (str-cat "<" (run) ">"))
(assert (a (x 1)))
(str-cat (run))
(assert (a (x 3)))
(create$ x (run) y)
(assert (a (x 4)))
(runner)
(assert (a (x 5)))
(progn (run 1) (printout t "between" crlf) (run))
(facts)
(eq (clear) 1)
(list-defrules)
(progn (clear) (build "(defrule r => (printout t 1 crlf) (printout t 2 crlf))") (printout t "after" crlf) (reset) (run) (printout t "end" crlf))
(list-defrules)
(create$ (clear) (build "(deftemplate b (slot y))") (assert-string "(b (y 7))") (fact-slot-value 1 y))
(facts)
(exit)
