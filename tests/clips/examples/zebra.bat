(load "zebra.clp")
(reset)
(run)
(exit)
