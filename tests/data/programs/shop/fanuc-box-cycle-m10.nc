O2001 (M10x1.5-6g external on a Fanuc lathe, G-code system A)
(G92 S2200 is how systems B and C clamp the spindle: read past, named, no thread)
(G90 X Z F is the turning box cycle: it cuts and returns to its start point X12 Z2, so after)
(the two box cycles the tool stands at X12 Z2, where the G76 passes start: pass 1, 0.4 deep)
(Q400, starts 0.4*tan 30 = 0.2309 before Z2 along the flank, at Z1.7691)
(M21, a tailstock code, is not one threadcheck knows: read past, named)
(G76 P010060 Q100 R0.02 / X8.160 Z-18 P920 Q400 F1.5: the last pass at X8.160)
G21 G99
T0101
G92 S2200
G96 S180 M3
G0 X12 Z2
G90 X10.5 Z-20 F0.25
X10.0
M21
T0303
G97 S800 M3
G76 P010060 Q100 R0.02
G76 X8.160 Z-18 P920 Q400 F1.5
G0 X50 Z50
M30
