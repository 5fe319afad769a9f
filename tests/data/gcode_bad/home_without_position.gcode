; options: no-home
; expect: 5:1: G28: the robot's home position is not set (home_mm in the robot file)
G0 X200 Y0
G28 G91 Z0 (Z only: accepted, nothing moves)
G28 (X and Y go home: needs the robot's home position)
