"""Models the equations of motion call: external torques and internal bodies.

- :mod:`~tumble.dynamics.models.torques`: constant and function torques, ``as_torque``.
- :mod:`~tumble.dynamics.models.rotors` (the gyrostat) and :mod:`~tumble.dynamics.models.damper`
  (the spherical nutation damper), joined into the equations of the whole by
  :mod:`~tumble.dynamics.models.internal`.
- :mod:`~tumble.dynamics.models.gravity`: the gravity-gradient torque; :mod:`~tumble.dynamics.models.lvlh`:
  the orbiting (LVLH) frame, roll-pitch-yaw axes and attitudes relative to it
  (its stability regions are :mod:`tumble.analysis.gravity_stability`);
  :mod:`~tumble.dynamics.models.orbit_gravity`: the torque along an ellipse or a TLE, and
  ``gravity_gradient_of(orbit)``, an orbit's torque model.
- :mod:`~tumble.dynamics.models.actuators` (magnetorquers, reaction wheels) and
  :mod:`~tumble.dynamics.models.sensors`, for the closed loop of :mod:`tumble.dynamics.control`.
- :mod:`~tumble.dynamics.models.drag`: Euler's equations with an aerodynamic drag about each
  principal axis, compiled (the fit's model).

A new model (torque, actuator, internal body) is a new module here; the methods in
:mod:`tumble.dynamics.methods` see it only through the right-hand side or the kicks it provides.
What the models act in (orbits, ephemerides, magnetic fields, sidereal time, the Earth's
constants) is :mod:`tumble.dynamics.environment`, below them: the models import it, never the reverse.
The public names are exported from :mod:`tumble.dynamics`.
"""
