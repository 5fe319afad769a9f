; LightBurn-style GRBL program written for the stiffpath tests
; GRBL device profile, absolute coords
; Bounds: X10 Y10 to X50 Y40
G00 G17 G40 G21 G54
G90
M4
; Cut @ 1200 mm/min, 60% power
M8
G0 X10Y10
; Layer C00
G1 X50S600F1200
G1 Y40
G1 X10
G1 Y10
; Layer C01: a circle at 30% power
G0 X20Y25
G2 X20Y25 I10J0S300F3000
M9
G1S0
M5
G90
; return to user-defined finish pos
G0 X0 Y0
M2
