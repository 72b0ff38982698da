(load "wordgame.clp")
(reset)
(run)
(exit)
