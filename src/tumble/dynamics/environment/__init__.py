"""The spacecraft's surroundings: orbits, ephemerides, fields, sidereal time and the Earth's constants.

- :mod:`~tumble.dynamics.environment.earth`: the Earth's constants (``MU_EARTH``, ``R_EARTH``,
  ``OMEGA_EARTH``), written once.
- :mod:`~tumble.dynamics.environment.orbit`: the circular orbit of the control runs
  (:class:`~tumble.dynamics.environment.orbit.CircularOrbit`) and its orbit-plane world frame;
  :mod:`~tumble.dynamics.environment.ephemeris`: a Keplerian ellipse and a two-line element
  set through SGP4; :mod:`~tumble.dynamics.environment.local_frame`: the orbit's nadir frame
  along any of them, its rate and angular acceleration (the nadir target's).
- :mod:`~tumble.dynamics.environment.magnetic`: the Earth's tilted dipole and a uniform field;
  :mod:`~tumble.dynamics.environment.igrf`: the full IGRF along an orbit, through ``ppigrf``.
- :mod:`~tumble.dynamics.environment.sun`: the Sun's low-precision ephemeris and the Earth's
  shadow (cylindrical, and conical with the penumbra).
- :mod:`~tumble.dynamics.environment.sidereal`: Julian dates and the Greenwich sidereal angle.
- :mod:`~tumble.dynamics.environment.tabulated`: vectors tabulated in time as piecewise cubics,
  the form in which the compiled closed-loop kernel reads the IGRF field and an orbit's position.

The environment describes where the body is and what it sits in; it exerts no torque itself.
The torque models of :mod:`tumble.dynamics.models` (the gravity gradient along an orbit,
``gravity_gradient_of(orbit)``) and the controllers of :mod:`tumble.dynamics.control` import it,
never the reverse (an import-linter contract in ``pyproject.toml``). A new orbit, ephemeris or
field model is a new module here. The public names are exported from :mod:`tumble.dynamics`.
"""
