(load "stove.clp")
(reset)
(run)
1
yes
no
yes
no
3
(exit)
