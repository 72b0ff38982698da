(watch facts)
(watch rules)
(watch activations)
(deftemplate machine (slot name) (slot type (allowed-symbols T1 T2 DELIVER)) (slot state (default IDLE)) (multislot loaded-with))
(deftemplate robot (slot name) (slot at) (slot holding (default NONE)))
(deftemplate task (slot id) (slot goal) (slot where) (slot state (default proposed)))
(defglobal ?*PRIORITY-DELIVER* = 50 ?*PRIORITY-FEED* = 20)
(deffunction travel-cost (?from ?to) (if (eq ?from ?to) then 0 else (+ 1 (str-length (str-cat ?from ?to)))))
(deffacts world
   (robot (name r1) (at ins))
   (machine (name m1) (type T1))
   (machine (name m2) (type T2))
   (machine (name d1) (type DELIVER))
   (puck s0 at ins))
(defrule feed-t1
   (declare (salience ?*PRIORITY-FEED*))
   (robot (name ?r) (holding NONE) (at ?pos))
   (puck s0 at ins)
   (machine (name ?m) (type T1) (state IDLE))
   (not (task (goal feed) (where ?m)))
   =>
   (assert (task (id (sym-cat feed- ?m)) (goal feed) (where ?m)))
   (printout t ?r " plans to feed " ?m " cost " (travel-cost ?pos ?m) crlf))
(defrule start-task
   ?t <- (task (id ?id) (state proposed) (where ?m))
   ?r <- (robot (name ?n) (holding NONE))
   ?p <- (puck s0 at ins)
   =>
   (modify ?t (state running))
   (retract ?p)
   (modify ?r (holding s0) (at ?m)))
(defrule finish-feed
   ?t <- (task (goal feed) (state running) (where ?m))
   ?r <- (robot (holding s0) (at ?m))
   ?mach <- (machine (name ?m) (loaded-with $?l))
   =>
   (modify ?mach (loaded-with $?l s0) (state PROCESSING))
   (modify ?r (holding NONE))
   (modify ?t (state done)))
(defrule produce
   (declare (salience ?*PRIORITY-DELIVER*))
   ?mach <- (machine (name ?m) (state PROCESSING) (loaded-with s0))
   =>
   (modify ?mach (state OUTPUT) (loaded-with))
   (assert (puck s1 at ?m)))
(defrule report
   (declare (salience -100))
   (task (id ?id) (state done))
   (puck ?kind at ?where)
   =>
   (printout t "task " ?id " done; " ?kind " waits at " ?where crlf))
(reset)
(agenda)
(run)
(facts)
(exit)
