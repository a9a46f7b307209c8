[G31 whose largest infeed I is a millionth of a micrometre: V1 makes 9.2e11 cuts]
G0 X22 Z5
G31 X20 Z-20 F1.5 U-0.92 I0.000000000001 V1
