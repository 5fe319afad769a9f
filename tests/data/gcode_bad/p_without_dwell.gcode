; expect: 3:14: P2: P belongs to G4 (dwell seconds) or G64 (blend tolerance)
G0 X200 Y0
G1 X210 F100 P2
