; bind of a global's multifield copies it: temporaries after it are freed as usual (5000
; calls fit the scratch), and a later store to the global leaves the local as it was
(defglobal ?*g* = (create$ a b c))
(deffunction f (?i) (bind ?x ?*g*) (bind ?y (create$ ?i ?i ?i ?i)) (length$ ?y))
(deffunction g () (bind ?s 0) (loop-for-count (?i 1 5000) (bind ?s (+ ?s (f ?i)))) ?s)
(printout t (g) crlf)
(deffunction h () (bind ?x ?*g*) (bind ?*g* (create$ z)) ?x)
(printout t (h) crlf)
(exit)
