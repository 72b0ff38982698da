; expect: 2:14 expected robotino-agent implements
(deftemplate MAIN::t (slot x))
(assert (t (x 1)))
(facts)
(exit)
