; expect: 2:16 expected constant
(deffacts d (a ?x))
(exit)
