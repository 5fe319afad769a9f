; expect: 3:4: P1000000: a dwell of 1e+06 s is longer than the longest block accepted, 3600 s (P is read in seconds)
G0 X200 Y0
G4 P1000000
