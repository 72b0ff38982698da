;;; Join-heavy scaling workload: two-step and four-step paths whose ends lie
;;; in the same group, over a random graph with two edges out of every node.
;;; Each rule joins four patterns on shared variables, so most of the work is
;;; in the beta network. Nodes and edges come from the data generator
;;; (robotino-agent bench, host-shim/src/bench/workloads.rs).
;;; The globals count firings so the engines' final lines can be compared.

(defglobal ?*reach2* = 0 ?*reach4* = 0)

(deftemplate node (slot id) (slot group))
(deftemplate edge (slot from) (slot to))
(deftemplate reach2 (slot from) (slot to))

(defrule two_step_same_group
   (edge (from ?a) (to ?b))
   (edge (from ?b) (to ?c))
   (node (id ?a) (group ?g))
   (node (id ?c) (group ?g))
   =>
   (bind ?*reach2* (+ ?*reach2* 1))
   (assert (reach2 (from ?a) (to ?c))))

(defrule four_step_same_group
   (reach2 (from ?a) (to ?c))
   (reach2 (from ?c) (to ?d))
   (node (id ?a) (group ?g))
   (node (id ?d) (group ?g))
   =>
   (bind ?*reach4* (+ ?*reach4* 1)))

(defrule report
   (declare (salience -100))
   =>
   (printout t "reach2 " ?*reach2* " reach4 " ?*reach4* crlf))
