; Long string results: str-cat and sym-cat build texts up to 2 KiB (our documented
; limit; CLIPS has none), format's %s takes a 1000-byte string whole (also padded and
; cut by a precision), implode$ 2005 bytes.
(deffunction rep (?s ?n) (bind ?r "") (loop-for-count ?n (bind ?r (str-cat ?r ?s))) ?r)
(str-length (rep "0123456789" 102))
(str-length (rep "0123456789" 103))
(str-length (rep "0123456789" 204))
(str-length (str-cat (rep "0123456789" 100) (rep "abcdefghij" 100) 1.5 x))
(str-length (sym-cat (rep "0123456789" 50) (rep "0123456789" 53)))
(str-length (sym-cat (rep "0123456789" 204)))
(bind ?a (rep "0123456789" 100))
(str-length (format nil "%s" ?a))
(str-length (format nil "%s%s" ?a ?a))
(str-length (format nil "%1010s|" ?a))
(str-length (format nil "%-1005s|" ?a))
(format nil "%.12s|" ?a)
(sub-string 995 1000 (format nil "x%sy" ?a))
(str-length (implode$ (create$ ?a ?a)))
(exit)
