; expect: 2:5: G1: an incremental (G91) first move needs a known start position
G91 G1 X10 F100
