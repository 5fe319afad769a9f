; options: strict
; expect: 5:1: G28: homing moves are not supported
; expect: 5:9: Z0: the robot moves in the XY plane only (no Z axis)
G0 X200 Y0
G28 G91 Z0
