(load "dilemma1.clp")
(reset)
(run)
(exit)
