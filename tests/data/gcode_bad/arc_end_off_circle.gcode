; expect: 3:1: G3: the end point is not on the arc: radius 10.0000 mm at the start, 10.5000 mm at the end
G0 X200 Y0
G3 X190 Y10.5 I-10 J0 F600
