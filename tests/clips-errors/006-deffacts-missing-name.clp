; expect: 2:11 expected name
(deffacts (a 1) (b 2))
(exit)
