; expect: 3:1: G81: canned cycles are not supported
G0 X200 Y0
G81 X210 Y0 R1
