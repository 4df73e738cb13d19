"""Solution methods: the method registry and each family of integrators.

- :mod:`~tumble.dynamics.methods.integrators`: the registry (``METHODS``, ``get_method``): each
  method's name, capabilities and integrator.
- :mod:`~tumble.dynamics.methods.exact`, :mod:`~tumble.dynamics.methods.exact_batch`,
  :mod:`~tumble.dynamics.methods.exact_omega`, :mod:`~tumble.dynamics.methods.exact_parameters`:
  the exact torque-free solution, one body and batched.
- :mod:`~tumble.dynamics.methods.geometric`: the splitting (structure-preserving, fixed-step)
  integrators.

A new method is a module here plus one entry in the registry in ``integrators``; ``simulate``,
``simulate_batch``, the CLI, scenario files and sweeps all find it there.
"""
