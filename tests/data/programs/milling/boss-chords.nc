(threadcheck test program: a 40 mm boss, 6 mm cutter, centre path R23 in 36 chords of 10 deg)
G21 G90 G17
G0 X23 Y0 Z2
G1 Z-1 F100
#1=10
WHILE [#1 LE 360] DO1
G1 X[23*COS[#1]] Y[23*SIN[#1]]
#1=#1+10
END1
G0 Z2
M30
