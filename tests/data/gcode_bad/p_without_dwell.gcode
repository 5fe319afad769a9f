; expect: 3:14: P2: P belongs to G4 (dwell), G64 (blend tolerance) or M62/M63, M106/M107 (output number)
G0 X200 Y0
G1 X210 F100 P2
