; options: strict
; expect: 4:4: comments do not nest: '(' inside a comment
G0 X200 Y0
(a (nested) comment)
