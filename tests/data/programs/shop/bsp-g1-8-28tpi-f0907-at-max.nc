(G1/8 A, 28 tpi, on a metric control: the lead 25.4/28 = 0.9071429 mm is written F0.907)
(full-profile insert, radial G92: d2 = tip X + 0.640327 P = X8.564 + 0.580868 = 9.144868; class A: 9.040..9.147)
(lead error per turn 0.907 - 0.9071429 = -0.1429 um; over LE = D = 9.728 mm, 10.724 turns, -1.532 um; cot 27.5 = 1.92098)
(functional d2 = 9.144868 + 0.002943 = 9.147811 > 9.147 by 0.811 um: the GO gauge stops though d2 alone passes)
G21 G97 S900 M3
T0202
G0 X12 Z2
G92 X9.4 Z-18 F0.907
X9.1
X8.85
X8.66
X8.564
X8.564
G0 X30 Z30
M30
