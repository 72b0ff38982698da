(deftemplate item (slot id (type INTEGER) (default 0)) (slot tag (default none))
  (multislot parts))
(deftemplate count (slot n (default 0)))
(deffacts start (count (n 0)) (item (id 1) (tag a) (parts x y)) (item (id 2) (tag b)))
(defglobal ?*limit* = 5 ?*seen* = (create$))
(deffunction twice (?x) (* 2 ?x))
(defrule step ?c <- (count (n ?n&:(< ?n ?*limit*))) =>
  (modify ?c (n (+ ?n 1))))
(defrule pair (item (id ?a) (tag ?t)) (item (id ?b&~?a) (tag ?t)) =>
  (bind ?*seen* (create$ ?*seen* ?a ?b)))
(defrule lonely (item (id ?i) (parts $?p)) (not (item (id ?j&:(> ?j ?i)))) =>
  (printout t lonely " " ?i " " (length$ ?p) crlf))
(defrule any-parts (exists (item (parts ? $?))) (test (> ?*limit* 0)) =>
  (printout t (twice ?*limit*) crlf))
