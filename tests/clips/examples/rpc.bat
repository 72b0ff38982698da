(load "rpc.clp")
(reset)
(run)
R
Yes
P
Yes
S
No
(exit)
