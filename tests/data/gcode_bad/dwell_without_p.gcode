; expect: 3:1: G4: a dwell needs P (seconds)
G0 X200 Y0
G4
