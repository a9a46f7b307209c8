(7/8-14 UNF-2A on an inch control: the lead 1/14 in = 0.0714286 in is written F.0714, its 0.0001 in increment)
(per turn 0.0714 x 25.4 - 25.4/14 = -0.725714 um; the finishing pass starts at Z0.2 less its flank shift K tan 30 = 0.026789 in)
(so it threads 1.173211 in = 29.7996 mm; a gauge engages LE = D = 22.225 mm, 12.25 turns: -8.890 um; times cot 30 = 1.7321: +15.398 um on d2)
O1414
G20 G97 S700 M3
T0303
G0 X1.0 Z0.2
G76 X0.7831 Z-1.0 K0.0464 D0.012 A60 F.0714
G0 X2.0 Z2.0
M30
