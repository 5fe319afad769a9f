; expect: 3:9: Q7: Q belongs to G64 (the tolerance for merging short lines)
G0 X200 Y0
G1 X210 Q7 F600
