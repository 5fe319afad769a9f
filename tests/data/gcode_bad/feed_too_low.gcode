; expect: 3:12: F0.001: feed 0.001 mm/min is below the slowest accepted, 1 mm/min
G0 X200 Y0
G1 X210 Y0 F0.001
