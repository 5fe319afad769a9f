; options: no-home
; expect: 4:1: G92: the current position is unknown (give the start or the home position, or move before G92)
G21 G90
G92 X0 Y0
G0 X10 Y0
