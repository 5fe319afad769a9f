; options: strict
; expect: 1:1: unexpected non-ASCII character
G0 X200 Y0
