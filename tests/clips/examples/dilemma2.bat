(load "dilemma2.clp")
(reset)
(run)
(exit)
