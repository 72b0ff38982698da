; A batch file with CRLF line ends, as Windows editors save them (2 of 16 programs by
; others in round 19): CLIPS runs a command at the first carriage return after it but
; echoes the file's text only at each newline, so a command's result comes before the
; echo of its last line, which follows the next prompt. (The last line ends in a bare
; newline: an (exit) ended by \r\n ends the transcript without one, at its \r.)
(deftemplate point
   (slot x)
   (slot y))

(defrule show (point (x ?x) (y ?y)) => (printout t "point " ?x " " ?y crlf))
(assert (point (x 1) (y 2)))   ; a comment after the command
(assert (point (x 3)
              (y 4)))
(+ 1 2) (+ 3 4)
; a comment line

(facts)
(run)
(printout t "done" crlf)
(exit)
