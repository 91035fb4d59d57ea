"""
Static tip angles
=================

The ISO 7176-1 static stability angles of the rigid chair with its brakes
locked (``stability.tipping``): the slope on which it tips toward the main
wheels, toward the casters and to each side (casters in their least stable
swivel orientation), for three chairs, from the chair's geometry and c.g.
(statics only, no dynamics).
"""

import matplotlib.pyplot as plt
import numpy as np

import stability
from stability import tipping
from stability.plotting.style import OKABE_ITO

names = ["ej-premier", "revised", "power-fwd"]
results = [tipping.tip_angles(stability.preset(n)) for n in names]
directions = list(tipping.DIRECTIONS)

fig, ax = plt.subplots(figsize=(8, 4.5), layout="constrained")
x = np.arange(len(directions))
width = 0.8 / len(names)
for i, (name, r) in enumerate(zip(names, results, strict=True)):
    values = [getattr(r, f"{d}_deg") for d in directions]
    ax.bar(x + (i - 1) * width, values, width, color=OKABE_ITO[i], label=name)
ax.set_xticks(x, [d.replace("_", " ") for d in directions])
ax.set_ylabel("static tip angle (deg)")
ax.set_title("Static tip angles (ISO 7176-1), brakes locked: three chairs (rigid-body statics)")
ax.legend(title="chair")

# %%
# What to conclude: the smallest bar of each chair is the direction in which
# it tips first on a slope with the brakes locked (named below). The revised
# chair, with its c.g. further from the casters than the E&J Premier's, is
# much harder to tip toward its casters, while the design sweep and the root
# locus show that moving the c.g. toward the casters is what lowers the
# directional growth rate: tip stability and directional stability pull the
# c.g. in opposite directions.
for name, r in zip(names, results, strict=True):
    angles = {d: getattr(r, f"{d}_deg") for d in directions}
    first = min(angles, key=angles.get)
    print(f"{name}: " + ", ".join(f"{d} {a:.1f} deg" for d, a in angles.items()) + f"; tips first {first}")
