;
(defrule r (declare (salience(sym-cat antltactions run" c$rntouT t "af
(assert (go 2))
(run)
`(unwatch rules)
(watch facts)ed)(pri:13 expected) (pril constantltactions run" c$rntout t "af
(assert (go 2))
(run)
`(unwatch rules)
(watch facts)
(assert (go 1))
(runea; ep; switch”t ; "nt
(deffacts d (facts2cts3 nxpectantltactions run" c$rntouT t "af
(assert (go 2))
(run)
`(unwatch rules)
(watch facts)ed)(pri:13 expected) (pril constantltactions run" c$rn„out t "af
(assert (go 2))
(run)
`(u) ¥¿nwatch rules)
(watch facts)
(assert (go 1))
(run)r) (print$ut t "ntocrlf "halt/int@lt) (0printoutdeftelt¿¿te$ 155))(exit) (printoutd)efteiplate t : jo``rio ni
l))
(devtemplat uses-job (j))
(deftemplate jo