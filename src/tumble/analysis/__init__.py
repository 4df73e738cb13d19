"""Analysis of motions (layer 3): stability of the principal axes, flips and their period; fitting
a measured tumble (the inertia ratios from a gyroscope record); the gravity-gradient stability
of a body at rest in its orbiting frame.

Principal axes are numbered 1, 2, 3 (ascending moments) or named ``"minor"``,
``"intermediate"``, ``"major"`` in every argument and every result (docs/conventions.md,
"Numbering the principal axes").
"""

from typing import TYPE_CHECKING

from .._lazy import lazy_package

if TYPE_CHECKING:  # the names, as the type checker sees them; each is imported on its first use
    from .fit import RecordingFit, RotationFit, Toss, fit_recording, fit_rotation
    from .gravity_stability import STABILITY_REGIONS, gravity_gradient_ratios, gravity_gradient_stability
    from .period_inversion import PeriodFamily, periods_consistent
    from .stability import (
        axis_of,
        circulation_axis,
        energy_momentum_gaps,
        flip_interval,
        flip_interval_asymptotic,
        flip_times,
        linearised_rate,
        perturbation_exponent,
        SpinPrediction,
        spin_prediction,
        stable_spin_range,
    )
    from .periods import (
        axis_precession_period,
        montgomery_angle,
        npa_periods,
        npa_periods_measured,
        period,
        polhode_solid_angle,
        precession_per_period,
        rotation_per_period,
        symmetric_top_rates,
    )
    from .summary import stability_report, trajectory_summary

lazy_package(__name__)

__all__ = [
    "STABILITY_REGIONS",
    "PeriodFamily",
    "RecordingFit",
    "RotationFit",
    "SpinPrediction",
    "Toss",
    "axis_of",
    "axis_precession_period",
    "circulation_axis",
    "energy_momentum_gaps",
    "fit_recording",
    "fit_rotation",
    "flip_interval",
    "flip_interval_asymptotic",
    "flip_times",
    "gravity_gradient_ratios",
    "gravity_gradient_stability",
    "linearised_rate",
    "montgomery_angle",
    "npa_periods",
    "npa_periods_measured",
    "period",
    "periods_consistent",
    "perturbation_exponent",
    "polhode_solid_angle",
    "precession_per_period",
    "rotation_per_period",
    "spin_prediction",
    "stability_report",
    "stable_spin_range",
    "symmetric_top_rates",
    "trajectory_summary",
]
