; expect: 3:1 expected ')'
(assert (a 1)
