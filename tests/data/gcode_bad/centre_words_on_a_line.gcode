; expect: 3:9: I5: I, J and R belong to G2/G3 arc moves
G0 X200 Y0
G1 X210 I5 F100
