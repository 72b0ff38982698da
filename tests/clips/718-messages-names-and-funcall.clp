; [CSTRCPSR4] names the construct without the module it was written with; an error in a
; deffunction called through funcall is reported once, with a [PRCCODE4] line per
; deffunction (scout4 #17, #19).
(deftemplate MAIN::initial-fact)
(deftemplate a (slot x))
(assert (a))
(deftemplate MAIN::a (slot y))
(deftemplate a (slot y))
(defmodule B (export ?ALL))
(deftemplate B::b (slot x))
(assert (b))
(deftemplate B::b (slot z))
(set-current-module MAIN)
(deffunction N ($?e) (<= (nth$ 1 ?e) 2))
(deffunction aplicar (?op $?e) (funcall ?op $?e))
(aplicar N x y)
(funcall N x)
(funcall + 1 a)
(exit)
