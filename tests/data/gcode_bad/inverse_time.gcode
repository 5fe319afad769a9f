; expect: 2:1: G93: only feed in units per minute (G94) is supported
G93 G1 X10 F2
