; expect: 6:4: X: a letter without a number
; expect: 7:12: F: a letter without a number
; expect: 8:4: P: a letter without a number
; every line is refused on its own: a file reports all its refusals at once
G0 X200 Y0
G1 Xnan Y0 F600
G1 X210 Y0 Finf
G4 Pinf
