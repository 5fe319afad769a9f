; expect: 2:1: M6: tool changes are not supported
M6
