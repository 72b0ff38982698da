; expect: 2:2 expected function
(defrul r (a) => )
(exit)
