(batch "runbench.bat")
(exit)
