; expect: 3:12: R2000000: beyond ±1000000 mm, the largest accepted for I, J and R
G0 X200 Y0
G2 X210 Y0 R2000000 F600
