; expect: 3:32 expected type
; keeps: [EXPRNPSR3] Missing function declaration for slower.
(deffunction slower (?s) (- ?s one))
(slower 3)
(exit)
