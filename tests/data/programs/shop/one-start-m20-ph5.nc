O2051 (M20xPh5P2.5-6g external, two starts, but only the first start is cut)
(the same G76 as two-start-m20-ph5.nc without its second cycle: start 2, 2.5 mm along Z, is missing)
G21 G97 S400 M3
T0101
G0 X22 Z2
G1 X19.9 Z0 F0.2 (the blank: 19.9, inside 6g's d 19.623 to 19.958)
G1 Z-33
G0 X24 Z10
T0303
G0 X24 Z8
G76 P010060 Q200 R0.02
G76 X16.806 Z-30 P1534 Q500 F5.0
G0 X50 Z50
M30
