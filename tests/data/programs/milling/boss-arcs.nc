(threadcheck test program: the 40 mm boss with a 6 mm cutter in G3 arcs)
(level Z-1 on R23.05, 0.05 mm off the boss; level Z-2 on R23, on size)
G21 G90 G17
G0 X23.05 Y0 Z2
G1 Z-1 F100
G3 X-23.05 Y0 I-23.05 J0
G3 X23.05 Y0 R23.05
G0 Z2
G0 X23 Y0
G1 Z-2
G3 X-23 Y0 I-23 J0
G3 X23 Y0 I23 J0
G0 Z2
M30
