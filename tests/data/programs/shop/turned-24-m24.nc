O2424 (M24x2-6g external: the program turns the blank to 24.0 before threading)
(6g's major diameter d is 23.962 max: a blank of 24.0 leaves a crest above it, a failure)
(the blank threadcheck uses is this turning, line 7, not an assumed one)
G21 G99 G97 S900 M3
T0101
G0 X26 Z2
G1 X24.0 Z0 F0.2
G1 Z-32
G0 X30 Z2
T0303
G97 S600 M3
G0 X26 Z5
G76 P010060 Q100 R0.02
G76 X21.546 Z-28 P1227 Q400 F2.0
G0 X50 Z50
M30
