; get-function-list: every function's name (no deffunctions), in CLIPS 6.30's
; order; the list's length differs (no COOL here), so the program checks
; membership and the relative order of functions both engines have
(deffunction f () 1)
(deffunction order-of ($?names)
   (bind ?all (get-function-list))
   (bind ?r (create$))
   (progn$ (?n ?all) (if (member$ ?n ?names) then (bind ?r (create$ ?r ?n))))
   ?r)
(multifieldp (get-function-list))
(> (length$ (get-function-list)) 250)
(member$ f (get-function-list))
(subsetp (create$ assert retract modify duplicate str-cat sym-cat + - * / if while
   switch progn$ foreach get-function-list timetag sequencep get-watch-item
   set-beta-memory-resizing get-beta-memory-resizing mv-append nth subset
   expand$ (sym-cat "(expansion-call)")) (get-function-list))
(symbolp (nth$ 1 (get-function-list)))
(order-of exit if while bind progn return break switch gensym seed random length$
   time mem-used options expand$ funcall apropos mv-append create$ printout read
   format eq neq and or not numberp stringp evenp oddp sequencep pointerp + - * /
   max min batch load save watch unwatch sort list-watch-items get-watch-item
   rest$ first$ nth$ member$ subsetp str-cat sym-cat str-length upcase eval build
   sin cos pi round fetch toss profile check-syntax reset clear refresh agenda run
   halt focus matches timetag set-strategy get-strategy
   set-beta-memory-resizing get-beta-memory-resizing ppdeffacts type
   deffunction-module get-defglobal-list facts assert retract str-assert
   fact-index find-fact do-for-all-facts get-deftemplate-list modify duplicate
   deftemplate-slot-names deftemplate-slot-defaultp set-current-module)
(order-of subset nth mv-replace member mv-subseq mv-delete str-explode str-implode
   mv-append wordp)
(get-function-list 1)
(funcall get-function-list 1)
(funcall get-function-list 1 2)
(> (length$ (funcall get-function-list)) 250)
(exit)
