; expect: 3:1: G1: a move of 100 mm at 1 mm/min lasts 6000 s, longer than the longest block accepted, 3600 s
G0 X200 Y0
G1 X300 Y0 F1
