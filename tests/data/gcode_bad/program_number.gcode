; options: strict
; expect: 3:1: O100: program numbers and subroutines are not supported
O100
