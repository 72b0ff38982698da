; Defglobal, deffunction and control-form syntax errors as CLIPS 6.30 shows
; them after ERROR: a global without `=`, with no value (EXPRNPSR2), a
; variable or a value where a global is due; a deffunction parameter given
; twice or after the wildcard; if, while, loop-for-count and
; progn$ with nothing where an expression is due (EXPRNPSR2); a case or a
; second default after the default ("switch function"). Nothing is kept.
(defglobal ?*ok* = 5)
(deffunction good (?x) (switch ?x (case 1 then one) (default other)))
(defglobal ?*a* 1)
(defglobal ?*b* = )
(defglobal ?x = 1)
(defglobal ?*c* = 1 ?*d*)
(defglobal ?*f* = 1 2)
(defglobal MAIN ?*h* = 3 junk)
(deffunction)
(deffunction f3 (?x ?x))
(deffunction f4 (?x $?y ?z))
(deffunction f6 () (if))
(deffunction f8 () (while))
(deffunction f9 () (while 1 (foo)))
(deffunction f10 () (loop-for-count))
(deffunction f12 () (progn$ (?x) 1))
(deffunction f13 () (if 1 then 2 else))
(deffunction f14 () (if 1 then 2 else 3 4))
(deffunction f15 () (switch 1 (default 2) (case 1 then 3)))
(deffunction f20 () (switch 1 (default 2) (default 3)))
(defrule r1 (a ?x) => (switch ?x (default 2) (case 1 then 3)))
(list-defglobals)
(list-deffunctions)
(list-defrules)
(good 1)
(good 2)
?*ok*
(exit)
