#!/usr/bin/env python3
"""Runs a command and writes its user CPU time (s, all threads, to the microsecond) to a file:
GNU time's %U has a resolution of 10 ms, as long as the runs of our small benchmark models.
  bench/usertime.py OUT_FILE COMMAND [ARGS...]   (exits with the command's status)"""
import os
import resource
import subprocess
import sys

if len(sys.argv) < 3:
    sys.exit(__doc__)
before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
status = subprocess.call(sys.argv[2:])
after = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
with open(sys.argv[1], 'w') as f:
    f.write(f'{after - before:.4f}\n')
sys.exit(status)
