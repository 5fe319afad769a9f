; options: strict
; expect: 3:1: M6: tool changes are not supported
M6
