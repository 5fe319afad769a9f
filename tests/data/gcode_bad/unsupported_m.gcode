; expect: 2:1: M98: unsupported M code
M98 P100
