; start: RepRapFirmware printer
M140 S{bed_temp} ; bed towards its temperature while homing
M104 S{nozzle_temp} ; nozzle towards its temperature while homing
G90 ; absolute coordinates
G28 ; home all axes
G1 Z5 F3000 ; lift the nozzle off the bed
M190 S{bed_temp} ; wait for the bed
M109 S{nozzle_temp} ; wait for the nozzle
M106 P0 S0 ; fan off until the first layer is done
