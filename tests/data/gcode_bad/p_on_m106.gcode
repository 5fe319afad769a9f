; expect: 3:6: P2: P belongs to G4 (dwell), G64 (blend tolerance) or M62/M63 (output number)
G0 X200 Y0
M106 P2
