; expect: 3:1: G92: G92 needs X and/or Y
G0 X200 Y0
G92
