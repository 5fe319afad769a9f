; expect: 3:9: unexpected character '#'
G0 X200 Y0
G1 X210 #1=5
