(load "stove.clp")
(reset)
(run)
3
(exit)
