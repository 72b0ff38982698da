(load "dilemma3.clp")
(reset)
(run)
(exit)
