; expect: 2:1: X200: no motion mode is active (G0, G1, G2 or G3 must come first)
X200 Y0
