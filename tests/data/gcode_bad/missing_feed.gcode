; expect: 3:1: G1: no feed rate (F) has been programmed
G0 X200 Y0
G1 X210
