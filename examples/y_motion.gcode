( stiffpath example: the thesis's y motion, fig. 4.7a )
( 150 mm along x = 222.132 mm from y = -75 to 75 mm, robot frame, mm )
G21 G90 G17 G94
G61
G0 X222.132 Y-75
M3 S1000
G1 Y75 F120000
M5
M2
