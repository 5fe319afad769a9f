( stiffpath example: a combined x-y motion, the triangle of fig. 4.7b )
( the thesis gives no dimensions; this one spans the workspace x 172.132..272.132, y -75..75 mm: )
( A = 187.132, -60   B = 257.132, -60   C = 222.132, 60 ; exact stop at every corner )
G21 G90 G17 G94
G61
G0 X187.132 Y-60
M3 S1000
G1 X257.132 Y-60 F120000
G1 X222.132 Y60
G1 X187.132 Y-60
M5
M2
