; Generated in the style of jscut for the stiffpath tests
G21         ; Set units to mm
G90         ; Absolute positioning
G1 Z2.5400 F2540      ; Move to clearance level

;
; Operation:    0
; Name:
; Type:         Pocket
; Paths:        1
; Direction:    Conventional
; Cut Depth:    0.2000
; Pass Depth:   0.2000
; Plunge rate:  127
; Cut rate:     1016
;

; Path 0
; Rapid to initial position
G1 X10.0000 Y0.0000 F2540
G1 Z0.0000
; plunge
G1 Z-0.2000 F127
; cut
G1 X10.0000 Y10.0000 F1016
G1 X0.0000 Y10.0000
G1 X0.0000 Y0.0000
G1 X10.0000 Y0.0000
; Retract
G1 Z2.5400 F2540
M2
