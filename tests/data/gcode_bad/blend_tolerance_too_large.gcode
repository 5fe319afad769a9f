; expect: 3:5: P2000: blend tolerance above the largest accepted, 1000 mm
G0 X200 Y0
G64 P2000
