; expect: 5:1: G41: cutter radius compensation is not supported
; expect: 5:5: D1: unsupported word
; expect: 6:1: G1: the first move must give both X and Y (the start position is unknown)
; (every refusal of the file is reported; the first move fails on its own account)
G41 D1
G1 X10 F100
