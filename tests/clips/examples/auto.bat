(load "auto.clp")
(reset)
(run)
no
yes
no
no
yes
(exit)
