; expect: 3:6: S-1: laser power must not be negative
G0 X200 Y0
M106 S-1
