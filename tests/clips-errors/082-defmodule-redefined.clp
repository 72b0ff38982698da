; expect: 5:12 expected not in use
; keeps: (A MAIN)
; a defmodule other than MAIN cannot be defined again: CLIPS's CSTRCPSR4
(defmodule A (export ?ALL))
(defmodule A)
(get-focus-stack)
(focus A)
(get-focus-stack)
(exit)
