(load "rx7.clp")
(reset)
(run)
7
(exit)
