; options: strict
; expect: 4:1: unexpected non-ASCII character
G0 X200 Y0

