; expect: 3:14: E5: unsupported word
G0 X200 Y0
G1 X210 F600 E5
