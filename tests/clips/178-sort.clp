; sort: a stable merge sort by a function that says when two values are out of order
; (its calls seen through a printout), multifields spliced, a bad function name or a failing
; comparison (the values come back unsorted).
(sort > 4 3 5 7 2 7)
(sort < 4 3 5 7 2 7)
(sort > (create$ 4 3 5) 1 (create$))
(deffunction cmp (?a ?b) (printout t "cmp " ?a " " ?b crlf) (> ?a ?b))
(sort cmp 3 1 2)
(sort str-compare a b)
(deffunction by-len (?a ?b) (> (str-length ?a) (str-length ?b)))
(sort by-len "ccc" "a" "bb" "d" "ee")
(sort nope 1 2)
(sort >)
(sort > a 1)
(deffunction cmp2 (?a ?b) (printout t "cmp " ?a " " ?b crlf) (> ?a ?b))
(sort cmp2 5 4 3 2 1 0)
(funcall sort > 3 1 2)
(exit)
