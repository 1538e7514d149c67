#!/usr/bin/python3
"""A closed loop in lock-step, in Python: drive WorkPartner (gen2 or gen3)
towards the wall of models/worlds/scanner_wall.xml and slow down from what
its laser scanner sees, to stand 1 m from the wall.

Started on a paused sim (simpartner-sim --startPaused=1 ...), the run is
fully determined by this controller: the same at any speed, on any
machine. Usage: lockstep_stop_at_wall.py [--lcm-url URL]
Run it with the python3 the module was built for (Debian's /usr/bin/python3,
docs/python.md), not another first on PATH.
"""
import argparse

import numpy as np
import simpartner

STOP_AT = 1.0        # [m] from the wall
WHEEL_RADIUS = 0.235  # [m]
PERIOD = 10          # steps between ticks: 100 Hz at 1 ms steps

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--lcm-url", dest="url", default=simpartner.DEFAULT_URL,
                    help="the bus, as every SimPartner program takes it")
sim = simpartner.Sim(parser.parse_args().url, program="lockstep_stop_at_wall")
wheels = ["Axle1Motor", "Axle2Motor", "Axle3Motor", "Axle4Motor"]
front = sim.model()["bodies"].index("FrontChassis")

for state in sim.lockstep(period=PERIOD):
    scan = sim.reading("Scanner")
    if scan is None:
        # The scanner publishes on request only unless given a rate [Hz]:
        # at the tick rate, each tick has the scan of its own step.
        sim.command("Scanner", "100", action="params")
        continue
    gap = np.min(scan["values"]) - STOP_AT
    speed = float(np.clip(2.0 * gap, 0.0, 1.0))  # [m/s]: slow down on the last 0.5 m
    for wheel in wheels:
        sim.set_velocity(wheel, [speed / WHEEL_RADIUS])
    if gap < 0.01 and np.linalg.norm(state["velocity"][front]) < 1e-3:
        print("stopped at tick %d (t = %.3f s): scanner %.4f m, front at x = %.6f m"
              % (state["step"], state["time"], np.min(scan["values"]), state["position"][front, 0]))
        break
