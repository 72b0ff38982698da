; logical support chains where one retraction leaves many facts unsupported at
; once (a fan of derived facts, each deriving more), facts with two supports that
; lose both in the same retraction, a derived fact retracted by a rule while
; others wait, and the sources asserted back.
(deftemplate src (slot id) (slot grp))
(defrule d1 (logical (src (id ?i) (grp ?g)) (on ?g)) => (assert (d1 ?i ?g)))
(defrule d2 (logical (d1 ?i ?g)) => (assert (d2 ?i)) (assert (both ?g)))
(defrule d2b (logical (d1 ?i ?g) (src (id ?i))) => (assert (both ?g)))
(defrule d3 (logical (d2 ?i) (not (veto ?i))) => (assert (d3 ?i)))
(defrule kill (declare (salience 10)) ?f <- (d3 ?i&:(= (mod ?i 4) 0)) (kill) => (retract ?f))
(defrule show (declare (salience -10)) (show) =>
  (printout t (length$ (find-all-facts ((?f d1)) TRUE)) " "
              (length$ (find-all-facts ((?f d2)) TRUE)) " "
              (length$ (find-all-facts ((?f d3)) TRUE)) " "
              (length$ (find-all-facts ((?f both)) TRUE)) crlf))
(deffacts start (on 1) (on 2)
  (src (id 1) (grp 1)) (src (id 2) (grp 1)) (src (id 3) (grp 1)) (src (id 4) (grp 2))
  (src (id 5) (grp 2)) (src (id 6) (grp 2)) (src (id 8) (grp 1)) (src (id 12) (grp 2)))
(watch facts)
(reset)
(run)
(assert (veto 2) (veto 5))
(run)
(retract 1)
(run)
(assert (kill))
(run)
(assert (on 1))
(run)
(retract 2)
(assert (show))
(run)
(facts)
(exit)
