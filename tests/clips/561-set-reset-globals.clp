; (set-reset-globals FALSE): reset keeps the defglobals' values; the setting returns
; the old one, takes any value but FALSE as TRUE and stays across clear.
(watch facts)
(watch rules)
(defglobal ?*x* = 10 ?*l* = (create$ a b))
(defrule count (tick) => (bind ?*x* (+ ?*x* 1)))
(get-reset-globals)
(reset)
(assert (tick))
(run)
?*x*
(set-reset-globals FALSE)
(get-reset-globals)
(bind ?*l* (create$ c))
(reset)
?*x*
?*l*
(assert (tick))
(run)
?*x*
(set-reset-globals TRUE)
(reset)
?*x*
?*l*
(set-reset-globals nil)
(get-reset-globals)
(set-reset-globals (create$))
(set-reset-globals)
(set-reset-globals 1 2)
(get-reset-globals 1)
(set-reset-globals FALSE)
(clear)
(get-reset-globals)
(defglobal ?*y* = 3)
(bind ?*y* 7)
(reset)
?*y*
(set-reset-globals TRUE)
(reset)
?*y*
(exit)
