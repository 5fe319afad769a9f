( stiffpath example: the thesis's x motion, fig. 4.7a )
( 100 mm along y = 0 from x = 172.132 to 272.132 mm, robot frame, mm )
( F120000 = 2 m/s, the default speed limit, so the move is limited by acceleration and jerk )
G21 G90 G17 G94
G61
G0 X172.132 Y0
M3 S1000
G1 X272.132 F120000
M5
M2
