; A file open for writing: what printout and format write is in the file at once,
; before close, so a reader of the same file sees it; a rule halted by an error
; before its close leaves what its printout wrote up to the error. A reader that
; reached the end stays at the end (C stdio's end-of-file flag), even after the
; writer adds more.
(open "w916.txt" o "w")
(printout o "line1" crlf "part")
(open "w916.txt" i "r")
(readline i)
(readline i)
(readline i)
(printout o "2" crlf)
(readline i)
(format o "fmt %d%n" 7)
(read i)
(close i)
(open "w916.txt" i "r")
(readline i)
(readline i)
(readline i)
(readline i)
(close i)
(close o)
(defrule grade
  (grade ?name $?marks)
  =>
  (open "g916.txt" out "a")
  (printout out ?name " " ?marks " " (/ (+ (expand$ ?marks)) 4) crlf)
  (close out))
(assert (grade erin 1.5 2.5 x 4.5))
(run)
(open "g916.txt" in "r")
(readline in)
(readline in)
(close in)
(close out)
(remove "w916.txt")
(remove "g916.txt")
(exit)
