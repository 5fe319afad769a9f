; expect: 2:1: G41: cutter radius compensation is not supported
G41 D1
G1 X10 F100
