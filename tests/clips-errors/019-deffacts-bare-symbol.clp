; expect: 2:19 expected '('
(deffacts d (a 1) b (c 2))
(exit)
