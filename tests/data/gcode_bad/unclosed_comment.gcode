; expect: 3:13: comment '(' is not closed on this line
G0 X200 Y0
G1 X210 F60 (unclosed
