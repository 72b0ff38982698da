; `sort` wants a symbol naming a function first: another value is [ARGACCES5] "symbol"
; (no value printed), a symbol that names no function or one that cannot take two
; arguments is its own message and FALSE.
(sort 8)
(sort 8.1)
(sort "a")
(sort [a])
(sort a)
(sort >)
(sort > 3 2 5 1 2)
(sort agenda 3 2 5 1 2)
(bind ?f "<")
(sort ?f 3 1 2)
(bind ?f <)
(sort ?f 3 1 2)
(deffunction try (?f) (sort ?f 2 1) (printout t "after" crlf))
(try 7)
(try <)
(exit)
