; expect: 3:10: unexpected character '.'
G0 X200 Y0
G1 X210.5.5 F100
