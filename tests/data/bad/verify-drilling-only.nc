(threadcheck's own bad case: a machining-centre program that only drills)
G17 G21 G90 G94
T3 M6
S2000 M3
G0 X10 Y10 Z5
G81 Z-12 R2 F200
X30
G80
M30
