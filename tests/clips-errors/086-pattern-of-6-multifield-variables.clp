; expect: 4:15 expected at most 5 multifield variables in one pattern
; keeps: ok1
(deffunction ok () 1)
(defrule six (a $?p $?q $?r $?s $?t $?u) => (printout t ?p ?q ?r ?s ?t ?u crlf))
(printout t ok (ok) crlf)
(exit)
