; expect: 3:1: G5.1: unsupported G code
G0 X200 Y0
G5.1 X1 I1
