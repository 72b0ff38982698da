(load "nematode.clp")
(reset)
(run)
no
(exit)
