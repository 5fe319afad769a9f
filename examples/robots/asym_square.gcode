(A 80 mm square in the middle of asym-5bar's measured rectangle, marked at 2 m/s)
G21 G90 G17 G94
G61
G0 X-40 Y170
M3 S1000
G1 X40 Y170 F120000
G1 X40 Y250
G1 X-40 Y250
G1 X-40 Y170
M5
M2
