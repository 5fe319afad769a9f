; expect: 2:1: G3: an arc cannot be the first move: its start point is unknown (move there first)
G3 X200 Y10 I-5 J5 F600
