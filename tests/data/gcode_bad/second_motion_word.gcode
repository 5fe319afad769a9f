; expect: 3:4: G1: a second motion word on one line (G0 at column 1)
G0 X200 Y0
G0 G1 X210 F100
