%M20X1-5.NC
[M20x1.5-6g on a Heidenhain MANUALplus lathe, DIN PLUS: threadcheck's own test program]
HEADER
#MATERIAL 42CrMo4
BLANK
N1 G20 X22 Z-40 K1
FINISHED
N2 G0 X20 Z0
N3 G1 Z-30 BR-1
MACHINING
N10 G14 Q0
N11 T3 G95 F0.2 G97 S800 M3
[V0 constant cross-section, no offset; B and P from F*S/1000]
N12 G0 X22 Z5
N13 G31 X20 Z-20 F1.5 U-0.92 I0.3 V0 H0
N14 G0 X22 Z5
[V1 constant infeed, offsets alternating at A30, no run-in or overrun]
N15 G31 X20 Z-20 F1.5 U-0.92 I0.3 V1 H3 A30 B0 P0
[single paths: a straight thread and its chained taper run-out]
N16 G0 X19.4 Z5
N17 G33 Z-18 F1.5
N18 G33 X22 Z-20
N19 G0 X24
N20 G0 Z5
N21 X18.8
N22 G33 Z-18 F1.5
N23 G33 X22 Z-20
N24 G0 X24
N25 G0 Z5
N26 X18.16
N27 G33 Z-18 F1.5
N28 G33 X22 Z-20
N29 G0 X24
N30 G14 Q0
N31 M30
END
