; expect: 6:4: X6000: moves to 12200 mm in the robot frame, beyond ±10000 mm, the largest accepted
; expect: 7:4: X6000: moves to 12200 mm in the robot frame, beyond ±10000 mm, the largest accepted
; three incremental moves of 6 m each stay below the word limit but walk the robot out of range
G0 X200 Y0
G91 G1 X6000 F600000
G1 X6000
G1 X6000
