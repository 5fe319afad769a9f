; Marlin-style laser program (the fan output drives the laser), written for the stiffpath tests
; saved on Windows: a byte-order mark, CRLF line ends and an end-of-file character
G21 ; mm
G90
M107
G0 X0 Y0 F3000
G0 X10 Y10
M106 S255
G4 P500 ; pierce for 500 ms
G1 X40 Y10 F600
G1 X40 Y30
M107
G0 X50 Y30
M106 S128
G1 X50 Y10 F600
G1 X70 Y10
M107
G0 X0 Y0
