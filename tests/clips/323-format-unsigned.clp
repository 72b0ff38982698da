; format's %u: an integer printed unsigned (a negative as its 64-bit two's
; complement), with width, `-`, `0` and precision as %d takes them; a float is
; truncated first; a symbol or string is a type error
(format nil "%u|%6u|%-6u|%06u|%.4u|%8.3u" 7 7 7 7 7 7)
(format nil "%u" -1)
(format nil "%u %u" -9223372036854775807 9223372036854775807)
(format nil "%u" 12.9)
(format nil "%u" -2.5)
(format nil "%d/%u/%x/%o" -3 -3 -3 -3)
(format nil "%u" abc)
(format nil "%u" "5")
(format t "unsigned %u%n" 300)
(deffunction show (?n) (format nil "[%3u]" ?n))
(show 5)
(show -5)
(exit)
