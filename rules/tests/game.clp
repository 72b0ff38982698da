;;; strategy: paper
;;; with: game
;;; Whole simulated games: production finishes, faults, the clock.

(deffacts game-test-setup
  (rf-machine (name M1) (type T3)) (rf-machine (name M2) (type T3))
  (rf-machine (name M3) (type T3)) (rf-machine (name M4) (type T2))
  (rf-machine (name M5) (type T2)) (rf-machine (name M6) (type T2))
  (rf-machine (name M7) (type T1)) (rf-machine (name M8) (type T1))
  (rf-machine (name M9) (type T1)) (rf-machine (name M10) (type T1))
  (active-gate D1))

;; Clock off: 20 S0 make 5 P and 15 junk; recycled, the junk makes more.
;; Every P leaves the game at the gate, so 20 pucks make 18 P (the last
;; two are left half-made: an S1 and an S0 cannot make a P); all junk
;; recycled: 18 x (12 + 5 + 6) + 19 S2 x (4 + 3) = 547.
(reset)
(assert (game-clock (enabled FALSE)))
(run)
(t-expect-game-over "game clock off: agent done" done)
(t-expect-score "game clock off: 18 P, 547 points" 547 18)
(t-report (= (length$ (find-all-facts ((?d decision)) TRUE))
             (length$ (find-all-facts ((?d decision)) (> ?d:n 0))))
          "game decisions logged" "")

;; Faults: a lost puck and a failed drive cost pucks but never deadlock.
(reset)
(assert (game-clock (enabled FALSE))
        (fault (at-decision 2) (kind lose-puck))
        (fault (at-decision 5) (kind drive-fail)))
(run)
(t-expect-game-over "game with faults: agent done" done)
(do-for-fact ((?s score)) TRUE
  ;; decision 2 carries an S0 (lost); decision 5 is a fetch that never
  ;; reaches the storage (nothing taken): 19 pucks left make 17 P.
  (t-report (and (= ?s:lost 1) (= ?s:p 17)) "game with faults: 1 lost, 17 P"
            (str-cat "lost " ?s:lost " P " ?s:p)))
(do-for-fact ((?d decision)) (= ?d:n 2)
  (t-report (and (eq ?d:status FAILED) (eq ?d:holding NONE))
            "game fault decision logged as FAILED, hands empty"
            (str-cat ?d:status " " ?d:holding)))

;; A short clock ends the game by time.
(reset)
(assert (game-clock (limit 120.0)))
(run)
(t-expect-game-over "game short clock: over by time" time)
(do-for-fact ((?d decision)) TRUE
  (t-report (<= ?d:time 120.0) (str-cat "game decision " ?d:n " within the clock")
            (str-cat "time " ?d:time)))
