; Inkscape Lasertools-style program for Marlin, written for the stiffpath tests
; the laser hangs on the fan output; the program starts where the head stands
M17 ; steppers on
G92 X0 Y0 ; here is the origin
G21
G90
M107
G1 F3000
G1 X10 Y0
M106 S255
G4 P0 ; wait for the moves to finish before the laser fires
G1 F600
G1 X20 Y0
G1 X20 Y10
G1 X10 Y10
G1 X10 Y0
M107
G1 F3000
G1 X0 Y0
M18 ; steppers off
