; CLIPS's parser checks a call's return type against the argument it is passed as:
; the older names (`mv-append`, `mv-subseq`, `mv-delete`, `mv-replace`, `str-explode`
; give a multifield, `str-implode` a string, `subset`, `wordp`, `pointerp` a symbol)
; are refused as numbers as their newer names are (ours computed `(+ 1 (mv-append a))`
; and printed 1 after the message). `nth` and `member` may give a number.
(+ 1 (mv-append a))
(+ 1 (mv-subseq 1 1 (create$ a)))
(+ 1 (mv-delete 1 (create$ a)))
(+ 1 (mv-replace 1 (create$ a) b))
(+ 1 (str-explode "a"))
(+ 1 (str-implode (create$ a)))
(+ 1 (subset (create$) (create$)))
(+ 1 (wordp a))
(+ 1 (pointerp a))
(+ 1 (nth 1 (create$ a)))
(+ 1 (member a (create$ a)))
(+ 1 (create$ a))
(+ 1 (subsetp (create$) (create$)))
(exit)
