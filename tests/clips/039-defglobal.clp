(watch facts)
(watch rules)
(defglobal ?*count* = 0 ?*name* = "robot" ?*list* = (create$ a b c))
(defglobal ?*derived* = (+ 10 ?*count*))
(deffunction bump () (bind ?*count* (+ ?*count* 1)))
?*count*
?*name*
?*list*
?*derived*
(bump)
(bump)
?*count*
(bind ?*name* "other")
?*name*
(defrule count-facts (thing ?) => (bump))
(reset)
?*count*
?*name*
(assert (thing 1) (thing 2) (thing 3))
(run)
?*count*
(exit)
