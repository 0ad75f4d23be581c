"""`python3 -m dissector.sim`: the simulator (dissector/sim/simulate.py), as `python3 -m dissector.sim.simulate`."""
import sys

from dissector.sim.simulate import main

sys.exit(main())
