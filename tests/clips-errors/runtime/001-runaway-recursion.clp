; A deffunction that recurses forever: stopped at the evaluation depth limit, the error
; names the limit and the function (and the rule it ran in); the program goes on.
; (Real CLIPS 6.30 crashes on this program, so it has no transcript.)
; prints: [ERROR] function calls nested deeper than the evaluation depth limit (...
; prints: [PRCCODE4] Execution halted during the actions of deffunction forever.
; prints: [PRCCODE4] Execution halted during the actions of defrule spin.
; prints: still working
(deffunction forever (?n) (+ 1 (forever (+ ?n 1))))
(forever 1)
(defrule spin => (printout t (forever 1) crlf))
(reset)
(run)
(printout t "still " working crlf)
(exit)
