(load "cam.clp")
(reset)
(run)
(exit)
