; str-cat, sym-cat and format evaluate and check their arguments one at a time: a wrong
; one stops the call before later arguments are evaluated (their side effects never
; happen); format checks its control string against the number of arguments before
; evaluating any directive's argument (scout4 #9).
(format nil "%s %s" 12 (printout t "side effect" crlf))
(str-cat (printout t "A" crlf) (create$ a) (printout t "B" crlf))
(str-cat (printout t "A" crlf) x)
(str-cat x (create$ a) (printout t "B" crlf))
(sym-cat x (create$ a) (printout t "B" crlf))
(format nil "%s" a (printout t "X" crlf))
(format nil "%d %s" a (printout t "Y" crlf))
(format nil "%d %s" 1 (printout t "Y" crlf))
(format nil "%d %s" 1 (create$ a) (printout t "Z" crlf))
(format nil "%s %s" (create$ a) (printout t "Z" crlf))
(str-cat 1 2.0 "a" b [c] (create$) (printout t "B" crlf))
(str-cat 1 (assert (foo)) (printout t "F" crlf))
(format nil "%d|%5.2f|%s|%%|%n" 3 2.5 ok)
(funcall format nil "%d-%s" 1 x)
(sort str-compare c a b)
; a recursion in a later argument never runs after a wrong one
(deffunction j (?l) (if (= (length$ ?l) 0) then "" else (format nil "%s %s" (nth$ 1 ?l) (j (rest$ ?l)))))
(j (create$ 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20))
(j (create$ a b c))
(exit)
