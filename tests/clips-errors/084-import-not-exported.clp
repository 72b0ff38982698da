; expect: 6:38 expected exports
; keeps: For a total of 2 defmodules.
; importing by name what the module does not export: CLIPS's MODULPSR1
(defmodule A (export deftemplate t1))
(deftemplate t1 (slot a))
(defmodule D (import A deftemplate t2))
(deftemplate A::t2 (slot b))
(list-defmodules)
(exit)
