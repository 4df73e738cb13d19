"""Rotational dynamics (layer 2): Euler's equations, torques, rotors and dampers, orbits and fields, integrators, trajectories."""

from typing import TYPE_CHECKING

from .._lazy import lazy_package

if TYPE_CHECKING:  # the names, as the type checker sees them; each is imported on its first use
    from .batch import BatchTrajectory, simulate_batch
    from .control import (
        BDot,
        Controller,
        ControlledRun,
        DetumbleThenPoint,
        MRPFeedback,
        NadirTarget,
        bdot_gain,
        pd_response,
        simulate_controlled,
    )
    from .euler import (
        angular_momentum,
        energy_momentum_gaps,
        euler_rhs,
        euler_rhs_tensor,
        kinetic_energy,
    )
    from .environment.ephemeris import KeplerOrbit, TLEOrbit
    from .environment.igrf import IGRFField
    from .environment.magnetic import DipoleField, UniformField
    from .environment.orbit import CircularOrbit
    from .methods.integrators import METHODS, Method, get_method
    from .models.actuators import Command, Magnetorquers, ReactionWheels
    from .models.dipole import ResidualDipole
    from .models.gravity import (
        GravityGradient,
        lvlh_state,
        orbit_frame_angles,
    )
    from .models.internal import SphericalDamper, gyrostat_rate
    from .models.orbit_gravity import OrbitGravityGradient, gravity_gradient_of
    from .models.sensors import Measurement, Sensors
    from .models.torques import ConstantTorque, FunctionTorque, TorqueModel, TorqueSum, as_torque
    from .simulate import DEFAULT_METHOD, FRAMES, simulate
    from .special.quaternion import quaternion_rate
    from .trajectory import Trajectory

lazy_package(__name__)

__all__ = [
    "DEFAULT_METHOD",
    "FRAMES",
    "METHODS",
    "BDot",
    "BatchTrajectory",
    "CircularOrbit",
    "Command",
    "ConstantTorque",
    "ControlledRun",
    "Controller",
    "DetumbleThenPoint",
    "DipoleField",
    "FunctionTorque",
    "GravityGradient",
    "IGRFField",
    "KeplerOrbit",
    "MRPFeedback",
    "Magnetorquers",
    "Measurement",
    "Method",
    "NadirTarget",
    "OrbitGravityGradient",
    "ReactionWheels",
    "ResidualDipole",
    "Sensors",
    "SphericalDamper",
    "TLEOrbit",
    "TorqueModel",
    "TorqueSum",
    "Trajectory",
    "UniformField",
    "angular_momentum",
    "as_torque",
    "bdot_gain",
    "energy_momentum_gaps",
    "euler_rhs",
    "euler_rhs_tensor",
    "get_method",
    "gravity_gradient_of",
    "gyrostat_rate",
    "kinetic_energy",
    "lvlh_state",
    "orbit_frame_angles",
    "pd_response",
    "quaternion_rate",
    "simulate",
    "simulate_batch",
    "simulate_controlled",
]
