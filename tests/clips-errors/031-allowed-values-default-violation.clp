; expect: 2:69 expected allowed
(deftemplate light (slot color (allowed-symbols red green) (default blue)))
(exit)
