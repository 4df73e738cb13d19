"""
Detumble, then point: one CubeSat mission
=========================================

A 3U CubeSat (moments ``(0.0067, 0.0419, 0.0419) kg m^2``) leaves its deployer at 20 deg/s about
its long axis in a 500 km sun-synchronous orbit. B-dot with the magnetorquers (Stickler &
Alfriend 1974) slows it until the gyroscope reads below 1 deg/s for a minute; then three
reaction wheels point it at a target fixed in the world by MRP feedback (Schaub & Junkins, sec.
8.3), while the magnetorquers unload the wheels (``MomentumDumping``). The dashed line marks the
switch. The total momentum of body and wheels changes only by the external impulse (of the
magnetorquers and the gravity gradient), to round-off.

To run in seconds this script has 1 A m^2 rods and eight times Avanzini & Giulietti's gain;
``examples/control/detumble_point.toml`` flies the same spacecraft from 20 deg/s with 0.2 A m^2
rods and the published gain, which takes about two orbits (``tumble simulate`` writes the same
figures).
"""

import math

import numpy as np

from tumble.dynamics import (
    BDot,
    DetumbleThenPoint,
    MRPFeedback,
    bdot_gain,
    gravity_gradient_of,
    simulate_controlled,
)
from tumble.dynamics.control.controllers import MomentumDumping
from tumble.dynamics.models.actuators import Magnetorquers, ReactionWheels
from tumble.dynamics.environment.magnetic import DipoleField
from tumble.dynamics.environment.orbit import CircularOrbit
from tumble.viz import control_figures

moments = np.array([0.0067, 0.0419, 0.0419])  # kg m^2, principal axes (axis 1 the long one)
orbit = CircularOrbit(altitude=500e3, inclination=math.radians(97.4))
wheels = ReactionWheels(np.eye(3), inertia=2e-5, max_torque=2e-3, max_speed=630.0)
gain = 8 * bdot_gain(orbit.mean_motion, orbit.inclination, moments[0])  # N m s
point = MRPFeedback(K=1.1e-3, P=6e-3, period=1.0, moments=moments, wheels=wheels)  # target: the world axes
mission = DetumbleThenPoint(BDot(gain=gain, period=1.0, form="normalized"), MomentumDumping(point, gain=1e-3),
                            switch_rate=math.radians(1.0), dwell=60.0)
run = simulate_controlled(moments, [math.radians(20.0), 0.0, 0.0], t_end=600.0, controller=mission,
                          field=DipoleField(orbit), gravity_gradient=gravity_gradient_of(orbit),
                          magnetorquers=Magnetorquers(1.0), wheels=wheels)
error = np.degrees(run.pointing_error(point.target))  # deg
budget = float(run.budget_error().max())  # kg m^2/s
print(f"pointing from t = {mission.switch_time:g} s; error {error[-1]:.2f} deg at {run.t[-1]:g} s; "
      f"momentum budget error {budget:.1e} kg m^2/s")

# %%
# The mission's figures, from ``control_figures``: rates, attitude error, wheels, dipole, momentum.

figures = control_figures(run, target=point.target, switch_time=mission.switch_time, title="detumble, then point")
fig_rates = figures["rates.png"]
fig_error = figures["attitude_error.png"]
fig_wheels = figures["wheels.png"]
fig_dipole = figures["dipole.png"]
fig_momentum = figures["momentum.png"]
