; end: generic Marlin printer
M104 S0 ; nozzle heater off
M140 S0 ; bed heater off
M107 ; fan off
G91 ; relative coordinates
G1 Z10 F600 ; lift the nozzle away from the print
G90 ; absolute coordinates
G1 X0 Y{bed_size_y} F3000 ; present the print
M84 ; motors off
