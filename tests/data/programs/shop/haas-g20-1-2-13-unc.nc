O2013 (1/2-13 UNC-2A on an inch Haas: one-block G76, X the final tip diameter in inches)
(X.4072 leaves d2 above its 2A maximum; the correction edits this X in inches)
G20 G97 S800 M3
T0303
G0 X0.6 Z0.2
G76 X0.4072 Z-1.0 K0.0471 D0.012 A60 F0.076923
G0 X1.0 Z1.0
M30
