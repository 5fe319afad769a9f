; expect: 3:9: X220: X is given twice on one line (also at column 4)
G0 X200 Y0
G1 X210 X220 F100
