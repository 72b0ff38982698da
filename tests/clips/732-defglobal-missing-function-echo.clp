; `[EXPRNPSR3]` in a defglobal's value: the global shown from its name up to the
; unknown function's name, also when it is nested and after other globals
(defglobal ?*e* = (foo 1))
(defglobal ?*e2* = (+ 1 (foo 1)))
(defglobal ?*a* = 1 ?*e3* = (bar))
(defglobal ?*b* = (create$ ?*a* (baz ?*a*)))
(defglobal MAIN ?*c* = 2 ?*d* = (+ ?*c* (str-cat (qux))))
(show-defglobals)
(exit)
