(threadcheck's own test program: an M10x1.5 external thread in five radial G92 passes)
(started at Z3, two leads before the face: the grooves lie at Z3 - k*1.5, centres on Z = 0 mod 1.5)
G21 G97 S600 M3
T0101
G0 X12. Z3.
G92 X9.4 Z-15. F1.5
X9.0
X8.6
X8.3
X8.062
G0 X20. Z50.
M30
