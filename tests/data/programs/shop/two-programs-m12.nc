%
O3102 (the thread, a subprogram written above its main program)
(M12x1.75-6g external: G92 passes at X11.4, X11.0, X10.6, X10.2, X9.9, X9.853)
G0 X14 Z4
G92 X11.4 Z-20 F1.75
X11.0
X10.6
X10.2
X9.9
X9.853
G0 X50 Z50
M99
O3101 (the main program: no other calls it; it calls O3102)
G21 G97 S600 M3
T0505
M98 P3102
M30
%
