; `<` ends a symbol or number in CLIPS (it may only start one): `4<56` is the two
; fields 4 and <56, `a<b<c` three, and `?f<-(a)` without spaces is a fact-address
; pattern. Variables, multifield variables and strings next to a `<`.
(watch rules)
(length$ (create$ 4<56))
(create$ 4<56 a<b<c <<a << <a<b)
(create$ 1.5<2 -3<x a< <)
(bind ?x 1)
(create$ ?x<2 x)
(bind ?v<w 3)
?v
(create$ a<"s" <"s")
(str-cat a<b)
(sym-cat <a<b)
(defrule take ?f<-(a ?n) => (printout t "took " ?n crlf) (retract ?f))
(defrule keep ?f<- (b $?r<c) => (printout t "kept " ?r crlf))
(defrule cmp (c ?y&:(< ?y 3)<x) => (printout t "cmp " ?y crlf))
(rules)
(assert (a 1) (b q <c) (c 2 <x))
(run)
(facts)
(exit)
