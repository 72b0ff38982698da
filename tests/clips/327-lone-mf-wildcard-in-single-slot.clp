; A lone `$?` in a single-field slot of a deftemplate pattern is read as `?` (the
; slot always holds one value); ppdefrule shows it as written. Anything after it in the
; slot, `&` too, is a syntax error showing the token after a space. A multifield
; variable there is refused once CLIPS has read the token after it, shown glued to it.
(deftemplate job (slot id) (slot state) (multislot tags))
(defrule any-state (job (id ?i) (state $?)) => (printout t "any-state " ?i crlf))
(defrule lone-first ?j <- (job (state $? ) (id ?i)) (not (job (id ?i) (tags x $?)))
   => (printout t "lone-first " ?i " " (fact-index ?j) crlf))
(defrule spread-over-lines (job (state $?
      )) => (printout t "spread" crlf))
(ppdefrule any-state)
(ppdefrule lone-first)
(ppdefrule spread-over-lines)
(defrule bad-and (job (state $?&~done)) =>)
(defrule bad-second (job (state $? ?s)) =>)
(defrule var-then-var (job (state $?x $?y)) =>)
(defrule var-then-word (job (state $?x done)) =>)
(defrule var-then-paren (job (id 1) (state $?x (a))) =>)
(defrule var-test-then-word (job (state $?x&:(> 1 0) b)) =>)
(defrule var-alone (job (state $?x)) =>)
(list-defrules)
(assert (job (id 1) (state open)) (job (id 2)) (job (id 3) (tags x)))
(matches any-state)
(run)
(exit)
