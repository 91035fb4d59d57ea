"""
Two chairs compared, and why they differ
========================================

``stability.compare`` puts chairs side by side on every measure and splits
the difference into the effect of each parameter difference applied alone
to the reference chair. Here the thesis's E&J Premier against its revised
design (exact model).
"""

import matplotlib.pyplot as plt
import numpy as np

import stability
from stability import compare
from stability.plotting.style import OKABE_ITO

a, b = stability.preset("ej-premier"), stability.preset("revised")
cmp = compare.compare([a, b])

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
for i, (label, curve) in enumerate(zip(cmp.labels, cmp.curves, strict=True)):
    ax1.plot(cmp.curve_speeds, curve, color=OKABE_ITO[i], lw=2, label=label)
ax1.axhline(0, color="0.3", lw=0.8)
ax1.set_xlabel("forward speed (m/s)")
ax1.set_ylabel("growth rate (1/s)")
ax1.set_title("Growth rate vs speed")
ax1.legend(title="chair")
effects = [e for e in cmp.effects[0].effects if e.growth_rate is not None]
effects.sort(key=lambda e: abs(e.growth_rate), reverse=True)
y = np.arange(len(effects))
ax2.barh(y, [e.growth_rate for e in effects],
         color=[OKABE_ITO[5] if e.growth_rate > 0 else OKABE_ITO[2] for e in effects])
ax2.set_yticks(y, [e.field for e in effects])
ax2.invert_yaxis()
ax2.axvline(0, color="0.3", lw=0.8)
ax2.set_xlabel("change of the growth rate at 0.75 m/s (1/s; > 0 less stable)")
ax2.set_title("Each difference applied alone")
fig.suptitle("ej-premier vs revised (exact model)")

# %%
# What to conclude: the bars say which parameter differences make the
# revised chair more or less stable than the E&J Premier, and by how much;
# the total and the interaction remainder are printed below.
es = cmp.effects[0]
print(f"total change {es.total_growth_rate:+.3f} 1/s, interactions {es.remainder_growth_rate:+.3f} 1/s")
for e in effects[:4]:
    print(f"{e.field}: {e.reference_value} -> {e.value}: {e.growth_rate:+.3f} 1/s")
