; expect: 4:764 expected fewer conditional elements
; keeps: ok1
(deffunction ok () 1)
(defrule many (c 0 ?x0) (c 1 ?x1) (c 2 ?x2) (c 3 ?x3) (c 4 ?x4) (c 5 ?x5) (c 6 ?x6) (c 7 ?x7) (c 8 ?x8) (c 9 ?x9) (c 10 ?x10) (c 11 ?x11) (c 12 ?x12) (c 13 ?x13) (c 14 ?x14) (c 15 ?x15) (c 16 ?x16) (c 17 ?x17) (c 18 ?x18) (c 19 ?x19) (c 20 ?x20) (c 21 ?x21) (c 22 ?x22) (c 23 ?x23) (c 24 ?x24) (c 25 ?x25) (c 26 ?x26) (c 27 ?x27) (c 28 ?x28) (c 29 ?x29) (c 30 ?x30) (c 31 ?x31) (c 32 ?x32) (c 33 ?x33) (c 34 ?x34) (c 35 ?x35) (c 36 ?x36) (c 37 ?x37) (c 38 ?x38) (c 39 ?x39) (c 40 ?x40) (c 41 ?x41) (c 42 ?x42) (c 43 ?x43) (c 44 ?x44) (c 45 ?x45) (c 46 ?x46) (c 47 ?x47) (c 48 ?x48) (c 49 ?x49) (c 50 ?x50) (c 51 ?x51) (c 52 ?x52) (c 53 ?x53) (c 54 ?x54) (c 55 ?x55) (c 56 ?x56) (c 57 ?x57) (c 58 ?x58) (c 59 ?x59) (c 60 ?x60) (c 61 ?x61) (c 62 ?x62) (c 63 ?x63) (c 64 ?x64) => (printout t ?x0 crlf))
(printout t ok (ok) crlf)
(exit)
