; progn$ over a global's multifield iterates the value it had when the loop began,
; whatever its body binds: the global itself and other multifield globals (which
; repack the globals' region), in nested loops over globals and in a deffunction left
; by return (issue 23: the host reads the cells in place, a repack keeps a copy).
; (CLIPS 6.30 itself reads freed memory for some rebinds, not repeated here.)
(defglobal ?*A* = (create$ a1 a2 a3 a4) ?*B* = (create$ b1 b2) ?*C* = 7 ?*D* = (create$))
(progn$ (?v ?*A*) (bind ?*A* (create$ x ?v)) (bind ?*B* (create$ ?*B* ?v)) (printout t ?v " "))
(printout t crlf ?*A* " " ?*B* crlf)
(bind ?*C* (create$ c1 c2 c3))
(progn$ (?v ?*B*)
   (progn$ (?w ?*C*) (bind ?*A* (create$ ?*A* ?w)) (bind ?*D* (create$ ?v ?w)) (printout t ?v ?w " ")))
(printout t crlf ?*A* " " ?*B* " " ?*C* " " ?*D* crlf)
(deffunction walk (?stop)
   (progn$ (?v ?*B*)
      (bind ?*B* (create$ ?*B* ?v ?v))
      (if (eq ?v ?stop) then (return ?v)))
   none)
(bind ?*B* (create$ m n o))
(printout t (walk n) " " ?*B* crlf)
(printout t (walk q) " " ?*B* crlf)
(bind ?*B* (create$ e1 e2 e3))
(progn$ (?v ?*B*) (bind ?*C* (create$ ?v ?v)) (bind ?*A* (create$ ?*C* ?*C*)) (printout t ?v " "))
(printout t crlf ?*A* " " ?*B* " " ?*C* crlf)
(exit)
