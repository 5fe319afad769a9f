; expect: 3:4: R5: a full circle needs its centre (I, J); R cannot place it
G0 X200 Y0
G2 R5 F600
