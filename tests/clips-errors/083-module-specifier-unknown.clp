; expect: 4:14 expected defined module
; lacks: t
; a module specifier naming no module: CLIPS's PRNTUTIL1, nothing defined
(deftemplate ZZZ::t (slot x))
(list-deftemplates)
(exit)
