; a rule of 43 patterns (a connect-four board shown by one rule, lu1smgb/UGR-IC
; 4enraya.clp): hosts take up to 64 patterns, as CLIPS takes any number; its activation,
; firing and the match after a retract
(watch rules)
(defrule board (show) (c 1 ?v1) (c 2 ?v2) (c 3 ?v3) (c 4 ?v4) (c 5 ?v5) (c 6 ?v6) (c 7 ?v7) (c 8 ?v8) (c 9 ?v9) (c 10 ?v10) (c 11 ?v11) (c 12 ?v12) (c 13 ?v13) (c 14 ?v14) (c 15 ?v15) (c 16 ?v16) (c 17 ?v17) (c 18 ?v18) (c 19 ?v19) (c 20 ?v20) (c 21 ?v21) (c 22 ?v22) (c 23 ?v23) (c 24 ?v24) (c 25 ?v25) (c 26 ?v26) (c 27 ?v27) (c 28 ?v28) (c 29 ?v29) (c 30 ?v30) (c 31 ?v31) (c 32 ?v32) (c 33 ?v33) (c 34 ?v34) (c 35 ?v35) (c 36 ?v36) (c 37 ?v37) (c 38 ?v38) (c 39 ?v39) (c 40 ?v40) (c 41 ?v41) (c 42 ?v42) (c 43 ?v43)
   =>
   (printout t ?v1 ?v2 ?v3 ?v4 ?v5 ?v6 ?v7 ?v8 ?v9 ?v10 ?v11 ?v12 ?v13 ?v14 ?v15 ?v16 ?v17 ?v18 ?v19 ?v20 ?v21 ?v22 ?v23 ?v24 ?v25 ?v26 ?v27 ?v28 ?v29 ?v30 ?v31 ?v32 ?v33 ?v34 ?v35 ?v36 ?v37 ?v38 ?v39 ?v40 ?v41 ?v42 ?v43 crlf))
(deffacts d (show) (c 1 b) (c 2 c) (c 3 d) (c 4 e) (c 5 f) (c 6 g) (c 7 h) (c 8 i) (c 9 j) (c 10 k) (c 11 l) (c 12 m) (c 13 n) (c 14 o) (c 15 p) (c 16 q) (c 17 r) (c 18 s) (c 19 t) (c 20 u) (c 21 v) (c 22 w) (c 23 x) (c 24 y) (c 25 z) (c 26 a) (c 27 b) (c 28 c) (c 29 d) (c 30 e) (c 31 f) (c 32 g) (c 33 h) (c 34 i) (c 35 j) (c 36 k) (c 37 l) (c 38 m) (c 39 n) (c 40 o) (c 41 p) (c 42 q) (c 43 r))
(reset)
(run)
(retract 20)
(assert (c 19 zz))
(run)
(assert (show again))
(agenda)
(exit)
