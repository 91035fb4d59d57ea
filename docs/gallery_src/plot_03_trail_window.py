"""
The trail window: directional stability against caster shimmy
==============================================================

The caster trail is the designer's main lever against caster shimmy; does
it also buy directional stability? The chart computes, on a grid of
trail and speed, the chair's divergence rate and the shimmy mode's real part
(chair model with relaxation-length caster tires, exact model), and the
critical trail below which the casters shimmy.
"""

import matplotlib.pyplot as plt
import numpy as np

import stability
from stability import shimmy
from stability.plotting.style import OKABE_ITO

chair = stability.preset("ej-premier")
trails = np.linspace(0.01, 0.10, 10)                     # m
speeds = np.array([0.5, 1.0, 1.5, 2.0, 3.0])             # m/s
chart = shimmy.chair_trail_chart(chair, trails, speeds)

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4.2), layout="constrained")
for j, u in enumerate(speeds):
    ax1.plot(1e3 * trails, chart.divergence_rate[:, j], color=OKABE_ITO[j], label=f"{u:g} m/s")
    ax2.plot(1e3 * trails, chart.shimmy_real_part[:, j], color=OKABE_ITO[j], label=f"{u:g} m/s")
for ax in (ax1, ax2):
    ax.axhline(0.0, color="0.3", lw=0.8)
    ax.axvline(1e3 * chart.chair_trail, color="0.3", ls=":", lw=1)
    ax.set_xlabel("caster trail (mm)")
    ax.legend(title="speed", fontsize=8)
ax1.set_ylabel("yaw divergence rate (1/s)")
ax2.set_ylabel("shimmy mode real part (1/s; > 0: shimmy)")
ax1.set_title("Directional stability")
ax2.set_title("Caster shimmy")
fig.suptitle("Trail window: ej-premier (exact model, relaxed caster tires; dotted: the chair's trail)")

# %%
# What to conclude: over 10-100 mm the trail changes the yaw divergence rate
# by a few per cent at most, so it is not a stability lever; below the
# critical trail the shimmy mode is unstable. Choose the trail for shimmy
# (above the largest critical trail, with margin) and fix the divergence with
# the c.g. position, pin friction or assist.
spread = 100 * (chart.divergence_rate.max(axis=0) / chart.divergence_rate.min(axis=0) - 1)
for u, t, p in zip(speeds, chart.critical_trail, spread, strict=True):
    print(f"{u:g} m/s: critical trail {1e3 * t:.1f} mm; divergence rate varies {p:.1f} % over the trails")
