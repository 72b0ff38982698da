; while and loop-for-count take `do` or an action's `(` after the condition or
; range: a word (`then`), a constant, a variable or the loop's `)` is a syntax
; error CLIPS shows glued to the text before it; `do do` and `do` alone are fine
(watch facts)
(watch rules)
(deffunction w1 (?n) (while (> ?n 0) then (printout t ?n crlf) (bind ?n (- ?n 1))))
(deffunction w2 () (while FALSE))
(deffunction w3 () (while FALSE 3 (printout t x crlf)))
(deffunction w4 (?x) (while FALSE ?x))
(deffunction w5 (?n) (while (> ?n 0) do do (bind ?n (- ?n 1))) ?n)
(deffunction w6 () (while FALSE do))
(deffunction w7 (?n) (while (> ?n 0) (printout t "n=" ?n crlf) (bind ?n (- ?n 1))))
(deffunction l1 () (loop-for-count 2 then (printout t x crlf)))
(deffunction l2 () (loop-for-count 2))
(deffunction l3 () (loop-for-count (?i 1 2) "go" (printout t ?i crlf)))
(deffunction l4 () (loop-for-count (?i 1 3) (printout t "i=" ?i crlf)))
(deffunction l5 () (loop-for-count (?i 2) do (printout t "j=" ?i crlf)))
(defrule r
   (go ?n)
   =>
   (while (> ?n 0) then
      (bind ?n (- ?n 1))))
(list-deffunctions)
(w5 3)
(w6)
(w7 2)
(l4)
(l5)
(list-defrules)
(while (> 1 2) then (printout t never crlf))
(loop-for-count 1 then (printout t never crlf))
(loop-for-count (?k 1 2) do (printout t "k=" ?k crlf))
(exit)
