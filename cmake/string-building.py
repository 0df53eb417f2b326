#!/usr/bin/env python3
# Moved to scripts/string-building.py in 0.6.0; this forwarder is removed in 0.8.
import os, runpy, sys
print("cellforge: cmake/string-building.py moved to scripts/string-building.py (the old path goes in 0.8)", file=sys.stderr)
target = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts", "string-building.py")
sys.argv[0] = target
runpy.run_path(target, run_name="__main__")
