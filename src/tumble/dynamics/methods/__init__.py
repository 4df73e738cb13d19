"""Solution methods: the method registry and each family of integrators.

- :mod:`~tumble.dynamics.methods.integrators`: the registry (``METHODS``, ``get_method``): each
  method's name, capabilities and integrator.
- :mod:`~tumble.dynamics.methods.exact_kernel`: the exact torque-free solution, written once over
  arrays of bodies; its two fronts :mod:`~tumble.dynamics.methods.exact` (one body, ``FreeRotation``)
  and :mod:`~tumble.dynamics.methods.exact_batch` (N bodies); its parameters
  (:mod:`~tumble.dynamics.methods.exact_parameters`); and :mod:`~tumble.dynamics.methods.exact_omega`,
  omega alone in double precision for the fit's inner loop.
- :mod:`~tumble.dynamics.methods.geometric`: the splitting (structure-preserving, fixed-step)
  integrators.

A new method is a module here plus one entry in the registry in ``integrators``; ``simulate``,
``simulate_batch``, the CLI, scenario files and sweeps all find it there.
"""
