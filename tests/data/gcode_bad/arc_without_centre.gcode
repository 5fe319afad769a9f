; expect: 3:1: G2: an arc needs its centre (I, J) or its radius (R)
G0 X200 Y0
G2 X210 Y0 F600
