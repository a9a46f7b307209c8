(An M30x1.5 bolt: turned to Ø29.85 over the thread, then G76 to d3 = 30 - 2 x 0.92 = 28.16.)
(Written for threadcheck's tests: the thread a shop would cut, to be checked against a)
(designation given by mistake.)
G21 G18 G99
T0101
G97 S800 M3
G0 X31 Z2
G1 X29.85 F0.2
G1 Z-25
G0 X32 Z5
G76 P010060 Q100 R0.05
G76 X28.16 Z-20 P920 Q350 F1.5
M30
