; expect: 3:5: G18: only the XY plane (G17) is supported
G0 X200 Y0
G21 G18
