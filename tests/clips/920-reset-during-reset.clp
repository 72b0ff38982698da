; a reset asked for while a reset runs (from a deffacts value or a global's initial
; value) does nothing: the outer reset goes on, its facts and globals as usual.
(watch facts)
(watch rules)
(deffunction again () (reset) (printout t "after inner reset" crlf) done)
(defglobal ?*n* = (progn (reset) 5))
(deffacts d1 (first =(reset) x) (second =(again)))
(deffacts d2 (third ?*n*))
(defrule show (third ?x) => (printout t "third " ?x crlf))
(reset)
(facts)
(run)
(bind ?*n* 6)
(reset)
?*n*
(agenda)
(exit)
