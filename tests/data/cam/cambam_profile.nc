( Made using a CamBam-style writer for the stiffpath tests )
( Plate 40 x 20 with two rounded corners )
G21 G90 G91.1 G64 G40
G0 Z3.0
( T0 : 0.2 )
T0 M6
( Profile1 )
G17
M3 S1000
G0 X0.0 Y0.0
G0 Z1.0
G1 F300.0 Z-0.2
G1 F1200.0 X30.0
G3 X35.0 Y5.0 I0.0 J5.0
G1 Y15.0
G3 X30.0 Y20.0 I-5.0 J0.0
G1 X0.0
G1 Y0.0
G0 Z3.0
M5
M30
