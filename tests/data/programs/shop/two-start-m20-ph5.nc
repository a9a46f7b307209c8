O2052 (M20xPh5P2.5-6g external, two starts, one G76 per start)
(the lead is 5, the pitch 2.5: the second cycle starts 2.5 mm further along Z, Z10.5 for Z8)
(G76 P010060 Q200 R0.02 / X16.806 Z-30 P1534 Q500 F5.0: passes from 0.5 deep along the)
(square-root law to k = 1.534 below the crest X16.806 + 2 x 1.534 = 19.874; the full profile)
(leaves d2 = 16.806 + 2 x 0.7217 = 18.249 with its H/8 flat tip: mid 6g, 18.164 to 18.334)
G21 G97 S400 M3
T0101
G0 X22 Z2
G1 X19.9 Z0 F0.2 (the blank: 19.9, inside 6g's d 19.623 to 19.958)
G1 Z-33
G0 X24 Z10
T0303
G0 X24 Z8
G76 P010060 Q200 R0.02
G76 X16.806 Z-30 P1534 Q500 F5.0
G0 X24 Z10.5
G76 P010060 Q200 R0.02
G76 X16.806 Z-30 P1534 Q500 F5.0
G0 X50 Z50
M30
