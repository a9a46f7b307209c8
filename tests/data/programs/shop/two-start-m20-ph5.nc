O2052 (M20xPh5P2.5-6g external, two starts, one G76 per start)
(the lead is 5, the pitch 2.5: the second cycle starts 2.5 mm further along Z, Z10.5 for Z8)
(G76 P010060 Q200 R0.02 / X16.933 Z-30 P1534 Q500 F5.0: passes from 0.5 deep along the)
(square-root law to 1.534 = 0.61343 x 2.5, the ISO external thread depth h3)
G21 G97 S400 M3
T0303
G0 X24 Z8
G76 P010060 Q200 R0.02
G76 X16.933 Z-30 P1534 Q500 F5.0
G0 X24 Z10.5
G76 P010060 Q200 R0.02
G76 X16.933 Z-30 P1534 Q500 F5.0
G0 X50 Z50
M30
