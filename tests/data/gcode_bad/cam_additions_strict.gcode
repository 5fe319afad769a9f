; options: strict
; expect: 7:1: G43: tool length compensation is not supported
; expect: 7:5: H1: tool length offsets are not supported
; expect: 8:1: G18: only the XY plane (G17) is supported
; expect: 9:1: M100: unsupported M code
G0 X200 Y0
G43 H1
G18
M100
