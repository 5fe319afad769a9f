; expect: 3:4: M106: a second laser (M3/M4/M5/M106/M107/M62/M63) word on one line (M3 at column 1)
G0 X200 Y0
M3 M106
