; expect: 3:12: F2000000: feed 2e+06 mm/min is above the fastest accepted, 1000000 mm/min
G0 X200 Y0
G1 X210 Y0 F2000000
