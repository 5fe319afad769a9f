; expect: 3:1: G55: only the G54 work offset is supported (its origin comes from the configuration)
G0 X200 Y0
G55
