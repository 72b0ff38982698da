(load "animal.clp")
(reset)
(run)
yes
yes
yes
yes
yes
(exit)
