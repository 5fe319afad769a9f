; expect: 3:4: X: a letter without a number
G0 X200 Y0
G1 X Y5 F100
