"""Root loci of the linear models: against speed, against design parameters, against a gain.

Compute -> result dataclass -> plot (:mod:`stability.plotting`), as python-control does:
:func:`speed_locus` -> :class:`SpeedLocus`; :func:`parameter_locus` ->
:class:`ParameterLocus` (one batched eigenvalue call over chairs built with
:meth:`~stability.chair.Chair.replace`); :func:`gain_locus` -> :class:`GainLocus`
(from :func:`control.root_locus_map`).
"""

from __future__ import annotations

from stability.chair.design import DESIGN_PARAMETERS, LOCUS_PARAMETERS, Parameter, get_parameter, parameter_names
from stability.rootlocus.gain import GainLocus, closed_loop_matrices, gain_locus
from stability.rootlocus.parameter import ParameterLocus, parameter_loci, parameter_locus
from stability.rootlocus.speed import SpeedLocus, speed_locus

__all__ = [
    "Parameter",
    "DESIGN_PARAMETERS",
    "LOCUS_PARAMETERS",
    "parameter_names",
    "get_parameter",
    "SpeedLocus",
    "speed_locus",
    "ParameterLocus",
    "parameter_locus",
    "parameter_loci",
    "GainLocus",
    "gain_locus",
    "closed_loop_matrices",
]
