(batch "loadall")
(exit)
