; options: dwell-ms
; expect: 4:4: P4000000: a dwell of 4000 s is longer than the longest block accepted, 3600 s (P is read in milliseconds)
G0 X200 Y0
G4 P4000000
