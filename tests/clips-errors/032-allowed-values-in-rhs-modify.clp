; expect: 3:47 expected allowed
(deftemplate light (slot color (allowed-symbols red green)))
(defrule r ?l <- (light) => (modify ?l (color blue)))
(exit)
