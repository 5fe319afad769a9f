; expect: 3:4: X1000000000: coordinate beyond ±10000 mm, the largest accepted
G0 X200 Y0
G1 X1000000000 F600
