; expect: 2:2 expected function
(frobnicate 1 2)
(exit)
