; options: strict
; expect: 4:1: unexpected character '/'
G0 X200 Y0
/G1 X210 F600
