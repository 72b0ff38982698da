; `format` pads `%Ns` and `%-Ns` by bytes, as C's printf does in CLIPS 6.30: a UTF-8
; string with accented or Cyrillic letters gets fewer pad spaces.
(printout t (format nil "|%-10s|%10s|" "héllo" "año") crlf)
(printout t (format nil "|%-12s|%8s|" "Привет" "мир") crlf)
(printout t (format nil "|%-10s|" "abc") crlf)
(format t "%-15s %5d%n" "Camión" 12)
(format t "%-15s %5d%n" "Camion" 12)
(format t "|%-4s|%4s|%n" "ñññ" "€")
(format t "|%-6.4s|%6.2s|%n" "Ωmega" "éa")
(format t "|%-8s|%8s|%n" Località città)
(format t "%-21s%-20s%n" "Località" "Albergo")
(format t "|%010s|%n" "né")
(exit)
