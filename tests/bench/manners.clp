;;; Miss Manners: seat guests around a table so that every guest sits next to
;;; a guest of the other sex who shares at least one hobby.
;;;
;;; The classic Rete benchmark. Each `seating` fact is one step of a partial
;;; solution (id, parent id pid); `path` facts list who sits where in that
;;; partial solution; `chosen` facts stop a step from being retried with the
;;; same guest. The `context` fact moves the program through its phases.
;;; The guests, `last_seat` and the start facts come from the data generator
;;; (robotino-agent bench, host-shim/src/bench/workloads.rs).
;;;
;;; Salience makes the phase order explicit instead of relying on how an
;;; engine orders activations created by one assert.

(deftemplate guest (slot name) (slot sex) (slot hobby))
(deftemplate last_seat (slot seat))
(deftemplate seating
   (slot seat1) (slot name1) (slot name2) (slot seat2)
   (slot id) (slot pid) (slot path_done))
(deftemplate context (slot state))
(deftemplate path (slot id) (slot name) (slot seat))
(deftemplate chosen (slot id) (slot name) (slot hobby))
(deftemplate count (slot c))

;;; Seat any guest in seat 1 to start the first partial solution.
(defrule assign_first_seat
   ?ctx <- (context (state start))
   (guest (name ?n))
   ?cnt <- (count (c ?c))
   =>
   (assert (seating (seat1 1) (name1 ?n) (name2 ?n) (seat2 1)
                    (id ?c) (pid 0) (path_done yes)))
   (assert (path (id ?c) (name ?n) (seat 1)))
   (modify ?cnt (c (+ ?c 1)))
   (modify ?ctx (state assign_seats)))

;;; Extend a finished partial solution by one guest of the other sex who
;;; shares a hobby with the guest in its last seat and is not seated yet.
(defrule find_seating
   ?ctx <- (context (state assign_seats))
   (seating (seat2 ?s2) (name2 ?n2) (id ?id) (path_done yes))
   (guest (name ?n2) (sex ?sx) (hobby ?h))
   (guest (name ?g) (sex ~?sx) (hobby ?h))
   ?cnt <- (count (c ?c))
   (not (path (id ?id) (name ?g)))
   (not (chosen (id ?id) (name ?g) (hobby ?h)))
   =>
   (assert (seating (seat1 ?s2) (name1 ?n2) (name2 ?g) (seat2 (+ ?s2 1))
                    (id ?c) (pid ?id) (path_done no)))
   (assert (path (id ?c) (name ?g) (seat (+ ?s2 1))))
   (assert (chosen (id ?id) (name ?g) (hobby ?h)))
   (modify ?cnt (c (+ ?c 1)))
   (modify ?ctx (state make_path)))

;;; Copy the parent's seats into the new partial solution.
(defrule make_path
   (declare (salience 10))
   (context (state make_path))
   (seating (id ?id) (pid ?pid) (path_done no))
   (path (id ?pid) (name ?n) (seat ?s))
   (not (path (id ?id) (name ?n)))
   =>
   (assert (path (id ?id) (name ?n) (seat ?s))))

;;; All seats copied: the new partial solution is complete.
(defrule path_done
   ?ctx <- (context (state make_path))
   ?st <- (seating (path_done no))
   =>
   (modify ?st (path_done yes))
   (modify ?ctx (state check_done)))

;;; The last seat is taken: go and print the solution.
(defrule are_we_done
   (declare (salience 10))
   ?ctx <- (context (state check_done))
   (last_seat (seat ?last))
   (seating (seat2 ?last))
   =>
   (modify ?ctx (state print_results)))

;;; Seats are still free: look for the next guest.
(defrule continue
   ?ctx <- (context (state check_done))
   =>
   (modify ?ctx (state assign_seats)))

;;; Print each seat of the solution that reached the last seat.
(defrule print_results
   (declare (salience 10))
   (context (state print_results))
   (last_seat (seat ?last))
   (seating (id ?id) (seat2 ?last))
   ?p <- (path (id ?id) (name ?n) (seat ?s))
   =>
   (retract ?p)
   (printout t "seat " ?s " " ?n crlf))

(defrule all_done
   (context (state print_results))
   =>
   (halt))
