; A pattern whose join compares one of its fields with a variable bound earlier keeps
; its alpha matches in buckets, one per value compared, in the order the buckets were
; made, each bucket oldest first; `matches` lists them so. A bucket left empty is
; dropped: a later match with its value starts a new bucket at the end. Several
; compared fields make one bucket per combination; a `not` pattern is bucketed too;
; the same pattern first in a rule (nothing compared) lists in plain assert order.
(deftemplate slot-t (slot room) (slot day) (slot who))
(defrule by-room (want ?r) (slot-t (room ?r) (who ?w)) =>)
(defrule by-room-day (want ?r ?d) (slot-t (room ?r) (day ?d)) =>)
(defrule free-day (day ?d) (not (slot-t (day ?d))) =>)
(defrule plain (slot-t (room ?r) (who ?w)) =>)
(assert (want 3) (day mon) (day fri))
(assert (slot-t (room 2) (day mon) (who ann))
        (slot-t (room 1) (day tue) (who bob))
        (slot-t (room 2) (day tue) (who cy))
        (slot-t (room 3) (day mon) (who di))
        (slot-t (room 1) (day mon) (who ed)))
(matches by-room)
(matches by-room-day)
(matches free-day)
(matches plain)
; bucket 2 keeps its place while it has a match left
(retract 4)
(assert (slot-t (room 2) (day wed) (who fay)))
(matches by-room)
; bucket 1 empties: its next match makes a new bucket at the end
(retract 5 8)
(assert (slot-t (room 1) (day thu) (who gus))
        (slot-t (room 3) (day thu) (who hal)))
(matches by-room)
(matches free-day)
; a modified fact is a new match: it goes to the end of its (possibly new) bucket
(modify 7 (room 1))
(modify 9 (room 2))
(matches by-room)
(matches by-room-day)
; a rule defined later shares the memory and lists it in the same order
(defrule later (want ?r) (slot-t (room ?r) (who ?w)) (day ?d) =>)
(matches later)
(reset)
(assert (want 1) (slot-t (room 5)) (slot-t (room 1)) (slot-t (room 5)))
(matches later)
(exit)
