; expect: 3:5: G17.1: only the XY, XZ and YZ planes (G17, G18, G19) are supported
G0 X200 Y0
G21 G17.1
