; expect: 3:1: O100: subroutines and control flow (sub, call, if, while …) are not supported
; expect: 5:1: O100: subroutines and control flow (sub, call, if, while …) are not supported
o100 sub
G0 X200 Y0
o100 endsub
