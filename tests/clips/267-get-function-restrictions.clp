; get-function-restrictions: CLIPS's restriction string (least and most arguments,
; type codes) of functions of every group; a deffunction or unknown name is no
; function; argument errors
(get-function-restrictions +)
(get-function-restrictions *)
(get-function-restrictions **)
(get-function-restrictions create$)
(get-function-restrictions str-cat)
(get-function-restrictions sub-string)
(get-function-restrictions str-compare)
(get-function-restrictions replace$)
(get-function-restrictions insert$)
(get-function-restrictions nth$)
(get-function-restrictions format)
(get-function-restrictions printout)
(get-function-restrictions if)
(get-function-restrictions while)
(get-function-restrictions assert)
(get-function-restrictions retract)
(get-function-restrictions facts)
(get-function-restrictions exit)
(get-function-restrictions run)
(get-function-restrictions open)
(get-function-restrictions close)
(get-function-restrictions read)
(get-function-restrictions fact-slot-value)
(get-function-restrictions deftemplate-slot-names)
(get-function-restrictions ppfact)
(get-function-restrictions save-facts)
(get-function-restrictions funcall)
(get-function-restrictions sort)
(get-function-restrictions random)
(get-function-restrictions set-strategy)
(get-function-restrictions focus)
(get-function-restrictions dependencies)
(get-function-restrictions do-for-all-facts)
(get-function-restrictions floatp)
(get-function-restrictions clear)
(get-function-restrictions watch)
(get-function-restrictions list-watch-items)
(get-function-restrictions get-function-restrictions)
(printout t (get-function-restrictions mv-subseq) crlf)
(deffunction ff (?x) ?x)
(get-function-restrictions ff)
(get-function-restrictions no-such-function)
(get-function-restrictions "+")
(get-function-restrictions 1)
(get-function-restrictions)
(get-function-restrictions + -)
(deffunction all-of ($?names)
   (progn$ (?n ?names)
      (printout t ?n " " (get-function-restrictions ?n) crlf)))
(all-of abs acos agenda and any-factp asin assert-string atan batch batch* bind break
   build clear-focus-stack conserve-mem cos deftemplate-slot-allowed-values
   deftemplate-slot-cardinality deftemplate-slot-default-value deftemplate-slot-defaultp
   deftemplate-slot-existp deftemplate-slot-multip deftemplate-slot-range
   deftemplate-slot-singlep deftemplate-slot-types deg-rad delayed-do-for-all-facts
   delete$ delete-member$ dependents div do-for-fact dribble-off dribble-on duplicate eq
   eval evenp exp explode$ fact-existp fact-index fact-relation fact-slot-names
   find-all-facts find-fact first$ float foreach gensym gensym* get-auto-float-dividend
   get-char get-current-module get-deffacts-list get-deffunction-list get-defglobal-list
   get-defmodule-list get-defrule-list get-deftemplate-list
   get-dynamic-constraint-checking get-fact-duplication get-fact-list get-focus
   get-focus-stack get-incremental-reset get-reset-globals get-salience-evaluation
   get-sequence-operator-recognition get-static-constraint-checking get-strategy halt
   implode$ integer integerp length length$ lexemep list-deffacts list-deffunctions
   list-defglobals list-defmodules list-defrules list-deftemplates list-focus-stack load
   load* load-facts log log10 loop-for-count lowcase matches max mem-requests mem-used
   member member$ min mod modify multifieldp mv-append mv-delete mv-replace neq not
   nth numberp oddp operating-system or pi pointerp pop-focus ppdeffacts ppdeffunction
   ppdefglobal ppdefmodule ppdefrule ppdeftemplate progn progn$ put-char rad-deg
   read-number readline refresh-agenda release-mem remove rename replace-member$ reset
   rest$ return round rules seed set-auto-float-dividend set-current-module
   set-dynamic-constraint-checking set-fact-duplication set-incremental-reset
   set-reset-globals set-salience-evaluation set-sequence-operator-recognition
   set-static-constraint-checking setgen show-defglobals sin sqrt str-explode str-implode
   str-index str-length string-to-field stringp subseq$ subset subsetp switch sym-cat
   symbolp system tan time undeffacts undeffunction undefglobal undefrule undeftemplate
   unwatch upcase wordp != - / < <= <> = > >= first$)
(exit)
