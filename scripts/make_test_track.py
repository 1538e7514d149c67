#!/usr/bin/env python3
"""Writes models/worlds/test_track.xml: WorkPartner gen4 on a heightfield test
track modelled on run 4 of the original's validation (SPEC 8): a slope down
just before the 20 m mark, two bumps after it, planks lying across the track
near 30 m, about 40 m in all along +x, on slightly uneven snowy ground.

The original's figure of the track is not available, so the shapes and sizes
below are our reconstruction from that description; they are the single
source of the track (edit them here and re-run, never the XML):

    python3 scripts/make_test_track.py            # writes models/worlds/test_track.xml
    python3 scripts/make_test_track.py -o FILE    # somewhere else

Standard library only; the output is deterministic (fixed seed), so running
the script again reproduces the committed file byte for byte.
"""
import argparse
import math
import os
import random

# ---------------------------------------------------------------- the track
# Heightfield extent. Columns run along x (the track), rows along z (across).
X_MIN, X_MAX = -2.0, 42.0      # [m] the robot starts at x = 0 facing +x
Z_HALF = 5.0                   # [m] track is 10 m wide (z from -5 to 5)
DX = 0.1                       # [m] sample spacing along the track
DZ = 0.5                       # [m] sample spacing across it
MM = 0.001                     # samples are whole millimetres (scale 0.001)

START_FLAT = 2.0               # [m] no unevenness for x < 2 (the robot starts at rest)
SLOPE_START, SLOPE_END = 16.0, 19.5   # [m] slope down just before the 20 m mark
SLOPE_DROP = 0.5               # [m] height lost on the slope (max gradient 22 %, 12.6 deg)
BUMPS = [(22.5, 0.12, 1.5), (25.5, 0.12, 1.5)]  # (centre x, height, length) [m]
PLANKS_FLAT = (28.8, 31.2)     # [m] no unevenness under the planks (they lie flat)
PLANKS = [29.6, 30.4]          # [m] plank centres along x
PLANK_SIZE = (0.2, 0.05, 4.0)  # [m] width along the track, thickness, length across it
TRACK_END = 40.0               # [m] unevenness fades out by here
SNOW_AMPLITUDE = 0.015         # [m] largest height of the snow's unevenness
SNOW_MU = 0.5                  # Coulomb friction of rubber on packed snow (our choice)
SEED = 4                       # run 4
FLOOR_Y = -2.0                 # [m] a safety plane well below the track


def smoothstep(a, b, x):
    """0 below a, 1 above b, a smooth cubic ramp between."""
    if x <= a:
        return 0.0
    if x >= b:
        return 1.0
    t = (x - a) / (b - a)
    return t * t * (3.0 - 2.0 * t)


def profile(x):
    """Height of the track's centre line at x [m], without the snow."""
    h = 0.0
    if x > SLOPE_START:
        t = min(1.0, (x - SLOPE_START) / (SLOPE_END - SLOPE_START))
        h -= SLOPE_DROP * (1.0 - math.cos(math.pi * t)) / 2.0
    for centre, height, length in BUMPS:
        u = (x - centre) / length
        if abs(u) < 0.5:
            h += height * math.cos(math.pi * u) ** 2
    return h


def make_snow():
    """A smooth, deterministic unevenness: a few plane waves with random
    directions, wavelengths (1.5 to 6 m) and phases, scaled so that its
    largest value is SNOW_AMPLITUDE."""
    rng = random.Random(SEED)
    waves = []
    for _ in range(8):
        wavelength = rng.uniform(1.5, 6.0)
        angle = rng.uniform(-math.pi / 3, math.pi / 3)  # mostly across the track
        kx = 2 * math.pi / wavelength * math.cos(angle)
        kz = 2 * math.pi / wavelength * math.sin(angle)
        waves.append((kx, kz, rng.uniform(0, 2 * math.pi), rng.uniform(0.5, 1.0)))
    norm = sum(w[3] for w in waves)

    def snow(x, z):
        fade = (smoothstep(START_FLAT, START_FLAT + 1.0, x) *
                (1.0 - smoothstep(TRACK_END - 1.0, TRACK_END, x)) *
                (1.0 - smoothstep(PLANKS_FLAT[0] - 1.0, PLANKS_FLAT[0], x) *
                 (1.0 - smoothstep(PLANKS_FLAT[1], PLANKS_FLAT[1] + 1.0, x))))
        if fade == 0.0:
            return 0.0
        s = sum(a * math.sin(kx * x + kz * z + p) for kx, kz, p, a in waves)
        return SNOW_AMPLITUDE * fade * s / norm
    return snow


def samples():
    columns = int(round((X_MAX - X_MIN) / DX)) + 1
    rows = int(round(2 * Z_HALF / DZ)) + 1
    snow = make_snow()
    data = []
    for r in range(rows):
        z = -Z_HALF + r * DZ
        data.append([int(round((profile(X_MIN + c * DX) + snow(X_MIN + c * DX, z)) / MM))
                     for c in range(columns)])
    return rows, columns, data


def fmt(v):
    s = ("%.6f" % v).rstrip("0").rstrip(".")
    return "0" if s in ("", "-0") else s


def transformation(x, y, z, indent="    "):
    return (indent + "<transformation>\n" +
            indent + "  <T00>1</T00><T01>0</T01><T02>0</T02><T03>%s</T03>\n" % fmt(x) +
            indent + "  <T10>0</T10><T11>1</T11><T12>0</T12><T13>%s</T13>\n" % fmt(y) +
            indent + "  <T20>0</T20><T21>0</T21><T22>1</T22><T23>%s</T23>\n" % fmt(z) +
            indent + "</transformation>\n")


def world_xml():
    rows, columns, data = samples()
    flat = [v for row in data for v in row]
    low, high = min(flat) * MM, max(flat) * MM
    plank_y = profile(PLANKS[0]) + PLANK_SIZE[1] / 2
    description = (
        "WorkPartner gen4 on a heightfield test track after run 4 of the original's "
        "validation (SPEC 8; our reconstruction, the original's figure is not available). "
        "The robot starts at rest at x = 0 facing +x on level ground (height 0). "
        "Along the track (x): level to %g m, with a smooth snowy unevenness of at most "
        "%g cm from x = %g m; a slope down from %g to %g m (just before the 20 m mark) "
        "losing %g m (max gradient %.0f %%); two bumps %g m high and %g m long centred "
        "at %g and %g m; two planks (%g m wide, %g m thick, %g m long, fixed) lying "
        "across the track at %g and %g m on level ground; the unevenness fades out by "
        "%g m; the field ends at %g m. Ground: packed snow, mu %g. "
        "With the wheels at 1.5 rad/s the no-slip speed is 0.3525 m/s (the original "
        "robot made 34.5 m in 104.75 s). Generated by scripts/make_test_track.py."
        % (SLOPE_START, SNOW_AMPLITUDE * 100, START_FLAT, SLOPE_START, SLOPE_END,
           SLOPE_DROP, 100 * SLOPE_DROP * math.pi / (2 * (SLOPE_END - SLOPE_START)),
           BUMPS[0][1], BUMPS[0][2], BUMPS[0][0], BUMPS[1][0], PLANK_SIZE[0],
           PLANK_SIZE[1], PLANK_SIZE[2], PLANKS[0], PLANKS[1], TRACK_END, X_MAX, SNOW_MU))
    out = []
    out.append('<?xml version="1.0" encoding="UTF-8"?>\n')
    out.append("<!-- GENERATED by scripts/make_test_track.py: edit the script and re-run it,\n"
               "     not this file. SimPartner world file (see models/README.md). -->\n")
    out.append('<world name="TestTrack" version="1">\n')
    out.append("  <description>%s</description>\n" % description)
    out.append("  <gravity><x>0</x><y>-9.81</y><z>0</z></gravity>\n")
    out.append("  <!-- Not the ground: a safety floor %g m below the track's lowest point\n"
               "       (%g m), catching anything that leaves the heightfield. -->\n"
               % (round(low - FLOOR_Y, 3), round(low, 3)))
    out.append("  <surface><a>0</a><b>1</b><c>0</c><d>%s</d></surface>\n" % fmt(FLOOR_Y))
    out.append('  <collisionSpace type="hash"/>\n')
    out.append('  <material name="snow"><mu>%s</mu></material>\n' % fmt(SNOW_MU))
    out.append("  <!-- %d rows (along z, %g m apart, z = %g..%g) x %d columns (along x,\n"
               "       %g m apart, x = %g..%g); samples in millimetres (scale 0.001);\n"
               "       heights from %g to %g m. -->\n"
               % (rows, DZ, -Z_HALF, Z_HALF, columns, DX, X_MIN, X_MAX, low, high))
    out.append('  <heightfield rows="%d" columns="%d" material="snow">\n' % (rows, columns))
    out.append("    <width>%s</width>\n" % fmt(X_MAX - X_MIN))
    out.append("    <depth>%s</depth>\n" % fmt(2 * Z_HALF))
    out.append("    <scale>%s</scale>\n" % fmt(MM))
    out.append("    <offset>0</offset>\n")
    out.append("    <thickness>1</thickness>\n")
    out.append("    <position><x>%s</x><y>0</y><z>0</z></position>\n" % fmt((X_MIN + X_MAX) / 2))
    out.append("    <samples>\n")
    for r, row in enumerate(data):
        out.append("      <!-- row %d: z = %s -->\n" % (r, fmt(-Z_HALF + r * DZ)))
        for start in range(0, len(row), 20):
            out.append("      " + " ".join(str(v) for v in row[start:start + 20]) + "\n")
    out.append("    </samples>\n")
    out.append("  </heightfield>\n")
    for i, x in enumerate(PLANKS, 1):
        out.append('  <object type="Box" name="Plank%d" material="snow" static="true">\n' % i)
        out.append("    <size><x>%s</x><y>%s</y><z>%s</z></size>\n" % tuple(fmt(v) for v in PLANK_SIZE))
        out.append(transformation(x, plank_y, 0))
        out.append("  </object>\n")
    out.append("  <!-- gen4 at the start, wheels on the level start area (height 0). -->\n")
    out.append('  <robot name="WorkPartner" file="../robots/workpartner_gen4.xml"/>\n')
    out.append("</world>\n")
    return "".join(out)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    default = os.path.join(here, "..", "models", "worlds", "test_track.xml")
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default=os.path.normpath(default))
    args = parser.parse_args()
    text = world_xml()
    with open(args.output, "w") as f:
        f.write(text)
    print("wrote %s (%d bytes)" % (args.output, len(text)))


if __name__ == "__main__":
    main()
