(watch facts)
(watch rules)
(deffunction classify (?x)
   (if (not (numberp ?x)) then
      not-a-number
    else
      (if (< ?x 0) then negative
       else (if (= ?x 0) then zero else positive))))
(classify -3)
(classify 0)
(classify 2.5)
(classify abc)
(if TRUE then 1 else 2)
(if FALSE then 1 else 2)
(if FALSE then 1)
(if 0 then yes else no)
(if (create$) then yes else no)
(defrule decide
   (n ?x)
   =>
   (if (> ?x 5)
    then (assert (big ?x)) (printout t ?x " is big" crlf)
    else (assert (small ?x))))
(reset)
(assert (n 3) (n 8))
(run)
(exit)
