; expect: 3:9: F0: feed rate must be positive
G0 X200 Y0
G1 X210 F0
