#!/usr/bin/python3
"""Drive WorkPartner (gen3, flat_ground.xml) in a left turn for a few seconds
and plot the live run with matplotlib: the chassis track seen from above
(the ground is the x-z plane, y up) and the wheels' rates.

Usage: drive_and_plot.py [--lcm-url URL] [--seconds S] [--out FILE.png]
With no display (or with --out) the plot goes to a PNG (Agg backend).
Run it with the python3 the module was built for (Debian's /usr/bin/python3,
docs/python.md), not another first on PATH."""
import argparse
import os

import matplotlib

if not os.environ.get("DISPLAY"):
    matplotlib.use("Agg")  # no window without a display
import matplotlib.pyplot as plt  # noqa: E402

import simpartner  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lcm-url", dest="url", default=simpartner.DEFAULT_URL,
                        help="the bus, as every SimPartner program takes it")
    parser.add_argument("--seconds", type=float, default=5.0, help="sim seconds to drive")
    parser.add_argument("--out", help="write the plot to this PNG instead of a window")
    args = parser.parse_args()

    sim = simpartner.Sim(args.url)  # NoSim if no sim answers
    model = sim.model()
    chassis = model["bodies"].index("FrontChassis")
    axles = [model["joints"].index("Axle%d" % w) for w in range(1, 5)]

    sim.set_angle("TurnerMotor", [0.3], p=100, i=100)  # steer left, held stiffly
    for w in range(1, 5):
        # rad/s; the inner wheels (2, 3) a little slower in the turn
        sim.set_velocity("Axle%dMotor" % w, [3.6 if w in (2, 3) else 4.4])

    start = sim.state()["time"]
    times, x, z, rates = [], [], [], []
    t = start
    while t < start + args.seconds:
        state = sim.wait_until(t + 0.05)  # every 50 ms of sim time
        t = state["time"]
        times.append(t - start)
        x.append(state["position"][chassis, 0])
        z.append(state["position"][chassis, 2])
        rates.append([state["joint_rate"][a, 0] for a in axles])
    for w in range(1, 5):
        sim.set_velocity("Axle%dMotor" % w, [0.0])

    figure, (track, wheels) = plt.subplots(1, 2, figsize=(11, 4.5))
    track.plot(x, z)
    track.set_aspect("equal", adjustable="datalim")
    track.set(title="FrontChassis seen from above", xlabel="x [m]", ylabel="z [m]")
    for w in range(4):
        wheels.plot(times, [r[w] for r in rates], label="Axle%d" % (w + 1))
    wheels.set(title="wheel rates", xlabel="sim time since start [s]", ylabel="rate [rad/s]")
    wheels.legend()
    figure.tight_layout()
    if args.out or matplotlib.get_backend().lower() == "agg":
        out = args.out or "drive_and_plot.png"
        figure.savefig(out, dpi=100)
        print("drive_and_plot: %d states, plot in %s" % (len(times), out))
    else:
        plt.show()


if __name__ == "__main__":
    try:
        main()
    except simpartner.ClientError as error:
        raise SystemExit("drive_and_plot: %s" % error)
