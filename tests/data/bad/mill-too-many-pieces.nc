(600 levels of 1 um, one full circle each: 600 x 3 370 chords, more than mill checks)
G21 G90 G17
G0 X23 Y0 Z2
#1=0
WHILE[#1LT600]DO1
G1 Z-[[#1+1]*0.001] F100
G3 X-23 Y0 I-23 J0
G3 X23 Y0 I23 J0
#1=#1+1
END1
M30
