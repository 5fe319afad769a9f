; expect: 3:17: R4: radius 4.0000 mm is less than half the distance to the end point (5.0000 mm)
G0 X200 Y0
G2 X210 Y0 F600 R4
