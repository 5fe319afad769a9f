; options: strict
; expect: 4:9: Z-1: the robot moves in the XY plane only (no Z axis)
G0 X200 Y0
G1 X210 Z-1 F100
