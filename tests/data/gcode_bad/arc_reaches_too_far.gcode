; expect: 4:1: G2: the arc reaches beyond ±10000 mm in the robot frame, the largest accepted
; a full circle of 9 m radius about a centre 8.8 m left of the robot
G0 X200 Y0
G2 I-9000 J0 F600000
