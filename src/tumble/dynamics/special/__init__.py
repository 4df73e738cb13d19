"""Special functions under the dynamics: elliptic functions, Carlson integrals, double-double
arithmetic, quaternion algebra.

- :mod:`~tumble.dynamics.special.elliptic`: Jacobi elliptic functions and Legendre's integrals
  near ``m = 1`` (the ``Modulus``).
- :mod:`~tumble.dynamics.special.carlson`: Legendre's integrals of the first and third kind
  through Carlson's, safe against underflow; the AGM and ``cel`` kernels.
- :mod:`~tumble.dynamics.special.ddouble`: double-double arithmetic (``hi + lo``, about 32 digits).
- :mod:`~tumble.dynamics.special.quaternion`: products, conjugates, rotations of vectors, z-x-z
  angles and the kinematic rate of scalar-last quaternions, written out over arrays.

This room sits below every other part of tumble: it imports numpy and scipy only, never another
tumble module (an import-linter contract in ``pyproject.toml`` checks it). A new special function
or kinematic helper that models and methods both need goes here.
"""
