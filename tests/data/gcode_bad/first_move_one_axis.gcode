; expect: 2:1: G0: the first move must give both X and Y (the start position is unknown)
G0 X200
