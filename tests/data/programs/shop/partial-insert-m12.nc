O3112 (M12x1.75-6g external with a sharp partial-profile insert: G92 to X9.32)
(A sharp 60-degree V whose tip is at X9.32 is 2 x 0.5345 mm wider at the pitch line than)
(one at the basic d3 9.853, so d2 lands inside 6g; the root it leaves is the tip's 0.04 mm)
(radius and d3 is 9.32, under d3 min: only the form checks fail)
G21 G97 S600 M3
T0505
G0 X14 Z4
G92 X11.4 Z-20 F1.75
X10.6
X9.9
X9.5
X9.32
G0 X50 Z50
M30
