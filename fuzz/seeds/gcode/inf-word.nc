G0 Xinf Z5
