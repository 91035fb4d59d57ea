"""
A design sweep: growth rate over two design parameters
======================================================

A grid of chairs built from the E&J Premier by changing two chapter-8
design parameters at once, the c.g. ratio and the wheelbase ``s1 + s2``
(through :data:`stability.chair.design.DESIGN_PARAMETERS`, which says how each is
applied and keeps every other field), with the growth rate of the least
stable mode at 0.75 m/s for each (linear, exact model, free casters).
"""

import matplotlib.pyplot as plt
import numpy as np

import stability
from stability.chair.design import get_parameter
from stability.plotting.style import colormap

chair = stability.preset("ej-premier")
cg, wb = get_parameter("cg_ratio"), get_parameter("s1_plus_s2")
cg_values = np.linspace(*cg.span(chair), 15)
wb_values = np.linspace(*wb.span(chair), 15)
rate = np.full((wb_values.size, cg_values.size), np.nan)          # 1/s
for i, w in enumerate(wb_values):
    for j, g in enumerate(cg_values):
        try:
            c = cg.apply(wb.apply(chair, w), g)
        except ValueError:          # e.g. the c.g. outside the wheel contacts: no such chair
            continue
        rate[i, j] = stability.eigenvalues_vs_speed(c, [0.75])[0].real.max()

fig, ax = plt.subplots(figsize=(7.5, 5), layout="constrained")
cs = ax.contourf(cg_values, wb_values, rate, levels=12, cmap=colormap("cividis"))
ax.contour(cg_values, wb_values, rate, levels=cs.levels, colors="0.2", linewidths=0.4)
ax.plot(cg.current(chair), wb.current(chair), "o", color="white", mec="black", label="ej-premier as built")
fig.colorbar(cs, ax=ax, label="growth rate at 0.75 m/s (1/s)")
ax.set_xlabel(f"{cg.label} ({cg.unit})")
ax.set_ylabel(f"{wb.label} ({wb.unit})")
ax.set_title("Design sweep at 0.75 m/s: ej-premier (exact model, free casters)")
ax.legend(loc="upper right")

# %%
# What to conclude: the map shows the direction in which the two parameters
# reduce the growth rate most, and how far a redesign can go; nowhere on it
# does the rate reach zero, so geometry alone does not make this chair stable.
k = np.unravel_index(np.nanargmin(rate), rate.shape)
print(f"as built: {stability.eigenvalues_vs_speed(chair, [0.75])[0].real.max():.3f} 1/s; "
      f"lowest on the grid {rate[k]:.3f} 1/s at {cg.name} = {cg_values[k[1]]:.3f}, "
      f"{wb.name} = {wb_values[k[0]]:.3f} {wb.unit}; highest {np.nanmax(rate):.3f} 1/s")
