"""Colours of the toolkit's figures: colour-blind-safe colour maps and a qualitative palette.

Sequential data use ``viridis``/``cividis``; categories use the Okabe-Ito
palette (Okabe & Ito 2008, "Color Universal Design"), distinguishable with
the common colour-vision deficiencies.  No red-green colour map is used.
"""

from __future__ import annotations

import numpy as np
from matplotlib import colormaps
from matplotlib.colors import Colormap, ListedColormap

__all__ = ["OKABE_ITO", "colour", "colormap", "UNSTABLE", "MARK"]

#: Okabe-Ito palette (black left out: it is used for reference lines).
OKABE_ITO = ("#0072B2", "#E69F00", "#009E73", "#CC79A7", "#56B4E9", "#D55E00", "#F0E442", "#999999")
#: Shading and marks of unstable regions and critical points (vermillion).
UNSTABLE = "#D55E00"
#: Marks of special points (the chair's own value, censored values).
MARK = "#CC79A7"


def colour(i: int) -> str:
    """The ``i``-th colour of the qualitative palette (cycled).

    Parameters
    ----------
    i : int
        Index of the category.

    Returns
    -------
    str
        A hex colour.
    """
    return OKABE_ITO[i % len(OKABE_ITO)]


def colormap(name: str, on_white: bool = False) -> Colormap:
    """A registered matplotlib colour map by name.

    Parameters
    ----------
    name : str
        Colour map name (``"viridis"``, ``"cividis"``, ...).
    on_white : bool
        Cut the lightest 20 % off the light end (the yellow of viridis, plasma and cividis vanishes
        on a white page); used for lines.

    Returns
    -------
    matplotlib.colors.Colormap
    """
    cmap = colormaps[name]
    if not on_white:
        return cmap
    rgb = cmap(np.linspace(0.0, 1.0, 256))[:, :3]
    lum = rgb @ np.array([0.2126, 0.7152, 0.0722])
    keep = slice(0, 205) if lum[-1] > lum[0] else slice(51, 256)
    return ListedColormap(cmap(np.linspace(0.0, 1.0, 256))[keep], name=f"{name}_on_white")
