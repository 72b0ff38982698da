; an unbound variable read in a query test or a loop limit halts it: one message, no type error
(deftemplate p (slot x))
(assert (p (x 1)) (p (x 2)))
(find-all-facts ((?f p)) (eq ?f:x ?*u*))
(loop-for-count (?i 1 ?*n*) (printout t ?i crlf))
(do-for-all-facts ((?f p)) (eq ?f:x ?*u*) (printout t ?f crlf))
(do-for-all-facts ((?f p)) TRUE (printout t ?f ?v crlf))
(while ?w do (printout t x crlf))
(exit)
