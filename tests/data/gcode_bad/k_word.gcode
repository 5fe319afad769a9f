; expect: 3:12: K2: arcs are in the XY plane; give their centre with I and J
G0 X200 Y0
G2 X210 I5 K2 F100
