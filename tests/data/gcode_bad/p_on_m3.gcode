; expect: 3:4: P2: P belongs to G4 (dwell), G64 (blend tolerance) or M62/M63, M106/M107 (output number)
G0 X200 Y0
M3 P2
