; expect: 3:1: G1: cannot share a line with G4
G0 X200 Y0
G1 G4 P1 X210 F100
