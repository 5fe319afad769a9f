%
O1001 (NAMEPLATE)
(Fusion/HSM-style laser program written for the stiffpath tests; work coordinates, G54 at the plate centre)
(T1  D=0.2 CR=0. - ZMIN=0. - LASER CUTTER)
N10 G90 G94 G17 G91.1
N15 G21
(2D PROFILE1: a hole of radius 4 mm)
N20 T1 M6
N25 G54
N30 G0 X-4. Y0.
N35 G0 Z5.
N40 G1 Z0. F1000.
N45 M3 S1000
N50 G2 X-4. Y0. I4. J0. F600.
N55 M5
N60 G0 Z5.
(2D PROFILE2: a 40 x 20 mm outline with corners of radius 5 mm)
N65 G0 X-15. Y-10.
N70 G1 Z0. F1000.
N75 M3 S750
N80 G1 X15. F1200.
N85 G3 X20. Y-5. I0. J5.
N90 G1 Y5.
N95 G3 X15. Y10. I-5. J0.
N100 G1 X-15.
N105 G3 X-20. Y5. I0. J-5.
N110 G1 Y-5.
N115 G3 X-15. Y-10. I5. J0.
N120 M5
N125 G0 Z5.
N130 M9
N135 G28 G91 Z0.
N140 G90
N145 M30
%
