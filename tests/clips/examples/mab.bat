(load "mab.clp")
(reset)
(run)
(exit)
