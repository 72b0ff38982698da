; Later alpha tests that say a field is not a symbol (`?s&~far` after another test
; of the pattern), which the host's quick alpha path decides (`(not (eq ...))`).
; Same matches as CLIPS whatever the field holds: the symbol itself, a string of
; the same name, a number, a multislot's element (first, second), a comparison
; with a global, two or three such tests in a row, a `|` of them, a `~` of a
; comparison, an ordered fact's element; facts modified across the symbol and
; asserted later, a failing test before it (an error reported, no match), then a
; reset and a partial run.
(defglobal ?*g* = near)
(deftemplate robot (slot name) (slot x (default 0)) (slot state (default idle))
  (multislot tags))
(defrule far-away
  (robot (name ?n) (x ?x&:(> ?x 100)) (state ?st&~far))
  =>
  (printout t "far-away " ?n " " ?x " " ?st crlf))
(defrule two-nots
  (robot (name ?n) (x ?x&:(> ?x 5)) (state ?st&~far&~idle))
  =>
  (printout t "two-nots " ?n " " ?st crlf))
(defrule three-in-a-row
  (robot (name ?n) (x ?x&:(> ?x 0)&~7&~151) (state ~far&~idle&~moving))
  =>
  (printout t "three-in-a-row " ?n crlf))
(defrule not-global
  (robot (name ?n) (x ?x&:(>= ?x 0)) (state ?st&~:(eq ?st ?*g*)))
  =>
  (printout t "not-global " ?n " " ?st crlf))
(defrule not-or
  (robot (name ?n) (x ?x&:(> ?x 1)) (state ?st&~far|near))
  =>
  (printout t "not-or " ?n " " ?st crlf))
(defrule not-compare
  (robot (name ?n) (x ?x&:(> ?x 1)&~:(> ?x 200)))
  =>
  (printout t "not-compare " ?n " " ?x crlf))
(defrule not-tag
  (robot (name ?n) (x ?x&:(numberp ?x)&:(> ?x 2)) (tags ?t&~far $?))
  =>
  (printout t "not-tag " ?n " " ?t crlf))
(defrule not-second-tag
  (robot (name ?n) (x ?x&:(numberp ?x)&:(> ?x 2)) (tags ? ?t&~far))
  =>
  (printout t "not-second-tag " ?n " " ?t crlf))
(defrule ordered
  (st ?n ?v&:(numberp ?v)&:(> ?v 1) ?s&~far)
  =>
  (printout t "ordered " ?n " " ?v " " ?s crlf))
(defrule mover
  ?r <- (robot (name ?n) (x ?x&:(< ?x 3)))
  =>
  (modify ?r (x (+ ?x 150)) (state (if (eq ?n r2) then far else moving))))
(deffacts start
  (robot (name r1) (x 1))
  (robot (name r2) (x 2) (state near))
  (robot (name r3) (x 120) (state "far"))
  (robot (name r4) (x 130) (state 7) (tags far a))
  (robot (name r5) (x 250) (state far) (tags a far))
  (robot (name r6) (x 6) (state busy) (tags b))
  (robot (name r9) (x 7) (state run) (tags))
  (st s1 5 far)
  (st s2 5 "far")
  (st s3 0 near)
  (st s4 x near)
  (st s5 9 ok)
  (robot (name r7) (x abc) (state idle) (tags a b)))
(reset)
(run)
(facts)
(assert (robot (name r8) (x 300) (state near) (tags near)))
(run)
(do-for-all-facts ((?f robot)) (eq ?f:name r3) (modify ?f (state far)))
(do-for-all-facts ((?f robot)) (eq ?f:name r5) (modify ?f (state gone)))
(agenda)
(run)
(reset)
(run 3)
(agenda)
(exit)
