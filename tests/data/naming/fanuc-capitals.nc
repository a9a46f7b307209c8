%
O2401 (SHAFT 4711)
(threadcheck's own test program: the thread named in capitals two lines above its G76)
T0101
G97 S800 M3
(THREAD M24X2 6G)
G0 X26 Z5
G76 P010060 Q100 R0.05
G76 X21.546 Z-30 P1227 Q350 F2.0
G0 X100 Z100
M30
%
