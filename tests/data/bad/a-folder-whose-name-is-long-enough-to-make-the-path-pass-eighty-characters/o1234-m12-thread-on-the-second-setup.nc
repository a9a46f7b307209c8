(a G92 pass through the axis, in a folder whose path passes 80 characters)
G0 X22 Z5
G92 X-1 Z-20 F1.5
