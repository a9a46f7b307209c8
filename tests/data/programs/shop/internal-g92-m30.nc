O3030 (M30x2 internal, G92 in a bore: the passes move outward, X28.2 to X30.0)
G21 G97 S500 M3
T0707
G0 X27 Z5
G92 X28.2 Z-25 F2.0
X28.8
X29.3
X29.7
X30.0
G0 Z50
M30
