; options: strict
; expect: 3:1: G91.1: arc centre modes are not supported (I and J are always relative to the start)
G91.1
