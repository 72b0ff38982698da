; Errors in a rule's (declare ...) as CLIPS 6.30 reports them: the salience
; out of range (PRNTUTIL9), not an integer (PRNTUTIL10, also computed), given
; twice (PRNTUTIL5), missing (EXPRNPSR2), an unknown or malformed item and an
; empty declare ("declare statement"), a bad auto-focus value, each with the
; rule shown after ERROR: up to where CLIPS stopped; nothing of them is kept.
(defrule good (declare (salience 5)) (x) => (printout t "good fired" crlf))
(defrule s1 (declare (salience 20000)) (x) =>)
(defrule s1b (declare (salience -10001)) (x) =>)
(defrule s2 (declare (salience a)) (x) =>)
(defrule s3 (declare (salience "a")) (x) =>)
(defrule s4 (declare (salience (+ 1 2.5))) (x) =>)
(defrule s4b (declare (salience 1.0)) (x) =>)
(defrule s5 (declare (salience 1) (salience 2)) (x) =>)
(defrule s6 (declare (salience)) (x) =>)
(defrule s7 (declare (salience 1 2)) (x) =>)
(defrule s8 (declare salience) (x) =>)
(defrule s9 (declare (auto-focus maybe)) (x) =>)
(defrule s10 (declare (auto-focus TRUE TRUE)) (x) =>)
(defrule s11 (declare) (x) =>)
(defrule s12 (declare (salience 1)) (declare (salience 2)) (x) =>)
(defrule s13 (declare (foo 1)) (x) =>)
(defrule s14 "a comment" (declare (salience 1) (bar)) (x) =>)
(defrule s15 (declare (salience 1) (auto-focus FALSE) 7) (x) =>)
(defrule ok2 (declare (salience 1) (auto-focus FALSE)) (x) => (printout t "ok2 fired" crlf))
(list-defrules)
(assert (x))
(run)
(exit)
