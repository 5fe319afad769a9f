; expect: 3:5: P-1: an output number is a whole number, 0 or more
G0 X200 Y0
M62 P-1
