; expect: 3:23 expected allowed
(deftemplate light (slot color (allowed-symbols red green)))
(assert (light (color blue)))
(exit)
