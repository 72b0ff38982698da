; expect: 2:8 expected fact
(assert)
(exit)
