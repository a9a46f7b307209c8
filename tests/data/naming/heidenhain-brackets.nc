%TC-NAME.NC
[threadcheck's own test program: a Heidenhain DIN comment names the thread]
MACHINING
N10 T3 G95 F0.2 G97 S800 M3
[ THREAD 1/2"-13 UNC-2A ]
N12 G0 X15 Z5
N13 G31 X12.7 Z-20 F1.954 U-1.2 I0.3 V0 H0
N14 G0 X40 Z50
END
