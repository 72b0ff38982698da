(load "rx7.clp")
(reset)
(run)
1
yes
yes
no
7
(exit)
