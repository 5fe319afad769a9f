; expect: 24:1: G41: cutter radius compensation is not supported
; expect: 25:1: G41: cutter radius compensation is not supported
; expect: 26:1: G41: cutter radius compensation is not supported
; expect: 27:1: G41: cutter radius compensation is not supported
; expect: 28:1: G41: cutter radius compensation is not supported
; expect: 29:1: G41: cutter radius compensation is not supported
; expect: 30:1: G41: cutter radius compensation is not supported
; expect: 31:1: G41: cutter radius compensation is not supported
; expect: 32:1: G41: cutter radius compensation is not supported
; expect: 33:1: G41: cutter radius compensation is not supported
; expect: 34:1: G41: cutter radius compensation is not supported
; expect: 35:1: G41: cutter radius compensation is not supported
; expect: 36:1: G41: cutter radius compensation is not supported
; expect: 37:1: G41: cutter radius compensation is not supported
; expect: 38:1: G41: cutter radius compensation is not supported
; expect: 39:1: G41: cutter radius compensation is not supported
; expect: 40:1: G41: cutter radius compensation is not supported
; expect: 41:1: G41: cutter radius compensation is not supported
; expect: 42:1: G41: cutter radius compensation is not supported
; expect: 43:1: G41: cutter radius compensation is not supported
; expect: … and 5 more
; 25 refused lines: the first 20 are listed, the rest counted
G0 X200 Y0
G41
G41
G41
G41
G41
G41
G41
G41
G41
G41
G41
G41
G41
G41
G41
G41
G41
G41
G41
G41
G41
G41
G41
G41
G41
