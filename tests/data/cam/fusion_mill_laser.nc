%
O1002 (BRACKET)
(Fusion-style milling post driving a laser, written for the stiffpath tests)
(T1  D=0.2 CR=0. - ZMIN=-0.1 - LASER)
(Output P0 lights a "done" LED; M100 starts the air-assist compressor)
N10 G90 G94 G17 G91.1
N15 G21
N20 G28 G91 Z0.
N25 G90
N30 T1 M6
N35 G54
N40 M100
N50 G0 X0. Y0.
N55 G43 Z2. H1
N60 M3 S1000
(lead-in: a ramp arc in XZ)
N65 G18 G3 X2. Z0. I2. K0. F600.
N70 G17
N75 G1 X20. F1200.
N80 G1 Y10.
N85 G1 X0.
N90 G1 Y0.
(lead-out: an arc in YZ)
N95 G19 G2 Y-2. Z2. J-2. K0.
N100 G17
N105 M5
N107 M62 P0 (DONE LED ON)
N110 G1 X-5. Y-5. F3000.
N115 M63 P0
N120 G28 G91 Z0.
N125 G49
N130 M30
%
