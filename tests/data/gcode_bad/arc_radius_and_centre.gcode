; expect: 3:18: R5: give the arc's centre (I, J) or its radius (R), not both
G0 X200 Y0
G2 X210 Y0 I5 J0 R5 F600
