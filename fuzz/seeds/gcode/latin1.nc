G0 X14 Z5 (café)
