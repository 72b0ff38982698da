(load "wine.clp")
(reset)
(run)
dry
red
full
average
unknown
unknown
unknown
unknown
unknown
unknown
(exit)
