; Appendix H names the BPG reserves but Debian's CLIPS 6.30 defines none of: the
; debugging extensions (show-fht, show-fpn, show-joins, show-opn, primitives-info,
; rule-complexity) and edit. Both engines: [EXPRNPSR3] at the prompt, in a rule's
; actions and in a deffunction (which is then not defined).
(watch facts)
(watch rules)
(edit)
(edit "x.clp")
(show-fht)
(show-fpn a)
(show-joins r)
(show-opn)
(primitives-info)
(rule-complexity r)
(defrule r (a) => (show-joins r))
(deffunction f () (rule-complexity r))
(list-defrules)
(list-deffunctions)
(printout t (eval "(show-opn)") crlf)
(printout t (check-syntax "(primitives-info)") crlf)
(printout t (build "(defrule r2 => (edit))") crlf)
(exit)
