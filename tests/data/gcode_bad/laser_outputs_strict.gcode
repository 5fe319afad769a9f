; options: strict
; expect: 8:1: M106: unsupported M code
; expect: 9:1: M62: unsupported M code
; expect: 10:1: M0: program pauses are not supported
; expect: 11:1: T1: tool selection is not supported
; expect: 11:4: M6: tool changes are not supported
G0 X200 Y0
M106 S255
M62 P0
M0
T1 M6
