; CLIPS's numeric functions (`+ - * / div mod **`, `= <> < <= > >=`) take their
; arguments one at a time (GetNumericArgument): the first that is no number (or a zero
; divisor of `/` or `div`, after truncation for `div`) is the last evaluated, so the
; side effects of later arguments never happen; `eq` and `neq` evaluate until a pair
; differs (`neq` until one equals the first). An argument whose call failed goes on with
; its value after the error (0 for arithmetic): a later one still runs unless that 0 is
; a divisor. Values are computed (globals, `bind`), so nothing is refused as read.
(defglobal ?*g* = 0 ?*a* = a)
(+ (bind ?*g* a) (bind ?*g* 5))
?*g*
(= (bind ?*g* a) (bind ?*g* 6))
?*g*
(<> (bind ?*g* b) (bind ?*g* 7))
?*g*
(< 1 (bind ?*g* c) (bind ?*g* 8))
?*g*
(>= (bind ?*g* d) 1)
?*g*
(+ 1 (bind ?*g* b) (bind ?*g* 8))
?*g*
(- 1 (bind ?*g* b) (bind ?*g* 9))
?*g*
(* 1 (bind ?*g* b) (bind ?*g* 9))
?*g*
(+ 1.5 (bind ?*g* c) (bind ?*g* 28))
?*g*
(/ 1 (bind ?*g* b) (bind ?*g* 10))
?*g*
(/ 1 (bind ?*g* 0) (bind ?*g* 11))
?*g*
(/ 7 (bind ?*g* -0.0) (bind ?*g* 12))
?*g*
(/ (bind ?*g* 0) (bind ?*g* 13))
?*g*
(div 1 (bind ?*g* 0) (bind ?*g* 14))
?*g*
(div 1 (bind ?*g* c) (bind ?*g* 15))
?*g*
(div 7 (bind ?*g* 0.5) (bind ?*g* 16))
?*g*
(div 7 (bind ?*g* -0.9) (bind ?*g* 17))
?*g*
(div 7 (bind ?*g* 1.5) (bind ?*g* 18))
?*g*
(div (bind ?*g* 0.5) (bind ?*g* 19))
?*g*
(mod (bind ?*g* c) (bind ?*g* 20))
?*g*
(** (bind ?*g* c) (bind ?*g* 21))
?*g*
(max 1 (bind ?*g* c) (bind ?*g* 22))
?*g*
(min 1 (bind ?*g* c) (bind ?*g* 23))
?*g*
(+ (bind ?*g* "1") (bind ?*g* 24))
?*g*
(+ (bind ?*g* (create$ 1)) (bind ?*g* 25))
?*g*
(< (bind ?*g* (create$)) (bind ?*g* 26))
?*g*
(> (bind ?*g* 3) (bind ?*g* 2) (bind ?*g* x) (bind ?*g* 27))
?*g*
(eq (bind ?*g* a) (bind ?*g* 6))
?*g*
(eq (bind ?*g* a) (bind ?*g* b) (bind ?*g* 6))
?*g*
(neq (bind ?*g* a) (bind ?*g* a) (bind ?*g* 6))
?*g*
(neq (bind ?*g* a) (bind ?*g* b) (bind ?*g* 7))
?*g*
(/ 1 (+ ?*a* 1) (bind ?*g* 30))
?*g*
(div 1 (+ ?*a* 1) (bind ?*g* 31))
?*g*
(+ 1 (+ ?*a* 1) (bind ?*g* 32))
?*g*
(= (+ ?*a* 1) (bind ?*g* 33))
?*g*
(+ 1 (+ 2 (bind ?*g* y) (bind ?*g* 34)) (bind ?*g* 35))
?*g*
(= (+ 2 (bind ?*g* y)) (bind ?*g* 36))
?*g*
(printout t (+ (bind ?*g* z) (bind ?*g* 37)) crlf)
?*g*
(exit)
