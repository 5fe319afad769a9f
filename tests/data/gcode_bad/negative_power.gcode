; expect: 3:4: S-5: laser power must not be negative
G0 X200 Y0
M3 S-5
