#!/usr/bin/env python3
"""Rolking's creep taken apart (docs/validation-summary.md, "Rolking's
held-wheel creep"): writes three variants of the shipped rolking sequence
(sequences/make_sequences.py rolking()) into a scratch directory and plays
each, and the shipped one, with bench/gait_slip at the steps given
(default 0.001 s), printing each run's speed against one stride per cycle.

  calf-held   as shipped: a standing foot's axle motor holds its angle to
              the calf; leg targets at 50 Hz
  smooth      leg targets every 2 ms (GAIT_EVERY 2; every step would pass
              the sequencer's 250,000 commands)
  ice-held    every axle turned at its calf's pitch rate on top of its
              ground speed / r, so a standing wheel keeps its angle to the
              ice; 50 Hz
  smooth ice-held   both

    bench/rolking_variants.py [--build DIR] [STEP ...]
"""
import argparse
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SEQUENCES = os.path.join(ROOT, "sequences")

# gait()'s wheel commands as shipped, and the ice-held replacement. The
# replacement must find the shipped text: a change there stops this script.
SHIPPED_WHEELS = '''            if not p[3][leg]:
                if state["last_phase"] != index:
                    w.hold(t, motor, WHEEL_TORQUE)
                continue
            if sample:
                velocity(w, t, motor, (body + relative[leg]) / WHEEL_RADIUS)'''
ICE_HELD_WHEELS = '''            ground = (body + relative[leg]) if p[3][leg] else 0.0
            pitch_rate = (calf_pitch(leg < 2, foot(t + h, leg)) -
                          calf_pitch(leg < 2, foot(t - h, leg))) / (2 * h)
            if sample:
                velocity(w, t, motor, ground / WHEEL_RADIUS + pitch_rate)'''
CALF_PITCH = '''
def calf_pitch(front, dx):
    link, height = 0.3, 0.48
    d = math.hypot(dx, height)
    beta = math.acos(d / (2.0 * link))
    gamma = math.atan2(-height, dx)
    return gamma + beta if front else gamma - beta
'''


def write_variant(out_dir, every, ice_held):
    with open(os.path.join(SEQUENCES, "make_sequences.py")) as f:
        source = f.read()
    if ice_held:
        if SHIPPED_WHEELS not in source:
            sys.exit("rolking_variants.py: make_sequences.py gait() changed; update SHIPPED_WHEELS")
        source = source.replace(SHIPPED_WHEELS, ICE_HELD_WHEELS) + CALF_PITCH
    namespace = {"__file__": os.path.join(SEQUENCES, "make_sequences.py"), "__name__": "variant"}
    exec(compile(source, "make_sequences.py", "exec"), namespace)
    namespace["HERE"] = os.path.join(out_dir, "sequences")
    namespace["GAIT_EVERY"] = every
    os.makedirs(namespace["HERE"], exist_ok=True)
    os.symlink(os.path.join(ROOT, "models"), os.path.join(out_dir, "models"))
    namespace["rolking"]()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"), help="build directory")
    parser.add_argument("steps", nargs="*", default=["0.001"], help="steps [s]")
    args = parser.parse_args()
    gait_slip = os.path.join(args.build, "bench", "gait_slip")
    variants = [("calf-held", 20, False), ("smooth", 2, False), ("ice-held", 20, True),
                ("smooth ice-held", 2, True)]
    with tempfile.TemporaryDirectory() as scratch:
        for name, every, ice_held in variants:
            out_dir = os.path.join(scratch, name.replace(" ", "_"))
            os.makedirs(out_dir)
            write_variant(out_dir, every, ice_held)
            run = subprocess.run([gait_slip, "--quick", "--models", os.path.join(out_dir, "models")] +
                                 args.steps, check=True, capture_output=True, text=True)
            for line in run.stdout.splitlines():
                if line.startswith("## "):
                    print("%-16s %s" % (name, line[3:]))


if __name__ == "__main__":
    main()
