; printout's special symbols vtab and ff write a vertical tab and a form feed (as crlf
; and tab); an infinite float prints inf.0 / -inf.0 and a NaN -nan.0 (CLIPS appends .0
; to C's %g text without a dot) (scout4 #10, #12).
(printout t "a" tab "b" vtab "c" ff "d" crlf)
(printout t "vtab" " " "ff" crlf)
(printout t (exp 1000) crlf)
(printout t (- 0 (exp 1000)) crlf)
(printout t (* 1e200 1e200) crlf)
(bind ?x (** 10.0 400))
(printout t ?x " " (str-cat ?x) " " (float ?x) crlf)
(exp 1000)
(create$ (exp 1000) (- 0 (exp 1000)))
(sym-cat (exp 1000))
(printout t (- (exp 1000) (exp 1000)) crlf)
(format nil "%f %g %e" (exp 1000) (exp 1000) (exp 1000))
(assert (big (exp 1000)))
(facts)
(exit)
