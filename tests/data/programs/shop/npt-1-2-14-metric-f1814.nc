(1/2-14 NPT, external, on a metric control: the lead 25.4/14 = 1.8142857 mm is written F1.814, its 0.001 mm increment)
(G92 R = radius at the start - radius at the end = -30/16/2 = -0.9375 over Z3.628 to Z-26.372; X is the end)
(by hand: per turn 1.814 - 1.8142857 = -0.2857 um; over L1 = 8.128 mm, what the gauge engages: -0.2857 x 8.128/1.8142857 = -1.280 um)
(times cot 30 = 1.7321: +2.217 um on the pitch diameter, the gauge off by 2.217e-3 / 0.0625 / 1.8142857 = 0.020 turn)
G21 G97 S600 M3
T0101
G0 X24 Z3.628
G92 X22.475 Z-26.372 R-0.9375 F1.814
X21.875
X21.275
X20.775
X20.275
X19.875
X19.575
X19.4615
G0 X30 Z50
M30
