;;; stubs.clp -- stand-ins for host functions, loaded only in real CLIPS.
;;; Our engine provides `distance` natively (geometry built-in); CLIPS
;;; gets this deffunction with the same meaning.

(deffunction distance
  "Euclidean distance between (x1, y1) and (x2, y2)."
  (?x1 ?y1 ?x2 ?y2)
  (sqrt (+ (* (- ?x2 ?x1) (- ?x2 ?x1)) (* (- ?y2 ?y1) (- ?y2 ?y1)))))
