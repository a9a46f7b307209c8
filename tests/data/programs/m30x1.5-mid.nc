(M30x1.5 bolt, no tool table: turned to Ø29.85 inside 6g's d [29.732, 29.968], threaded by)
(G76 to X28.053 so that a full-profile insert's tip there leaves d2 = 28.053 + 0.866 = 28.919,)
(the middle of 6g's d2 [28.844, 28.994]. Written for threadcheck's tests.)
G21 G18 G99
T0303
G97 S800 M3
G0 X31 Z2
G1 X29.85 F0.2
G1 Z-25
G0 X32 Z5
G76 P010060 Q100 R0.05
G76 X28.053 Z-20 P920 Q350 F1.5
M30
