"""Attitude knowledge: what the flight software knows of the attitude from its sensors.

- :mod:`~tumble.dynamics.estimation.static`: TRIAD and QUEST, the attitude from vector
  observations at one instant, with their covariances (:func:`triad`, :func:`quest`);
- :mod:`~tumble.dynamics.estimation.mekf`: the multiplicative extended Kalman filter
  (:class:`MEKF`), attitude error and gyroscope bias, propagated with the gyroscope and updated
  with vector sensors and a star tracker at their own rates.

The room reads the sensor models of :mod:`tumble.dynamics.models` and the formulas of
:mod:`tumble.dynamics.special`; the closed loop of :mod:`tumble.dynamics.control` calls it,
never the reverse (an import-linter contract in ``pyproject.toml``).
"""

from .mekf import MEKF
from .static import quest, triad

__all__ = ["MEKF", "quest", "triad"]
