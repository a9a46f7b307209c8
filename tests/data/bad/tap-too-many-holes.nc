(10 001 tapped holes along X: one more than threadcheck reads)
G90 G54 G17 G94
T1 M6
S600 M3
G0 X0 Y0 Z5
G99 G84 X0 Y0 Z-10 R2 F750
#1 = 1
WHILE [#1 LE 10000] DO1
X#1
#1 = #1 + 1
END1
G80
M30
