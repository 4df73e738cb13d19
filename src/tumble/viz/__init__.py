"""Pictures (the shell): figures, animations and the scene description they share.

Every ``figure_*`` function draws on a given matplotlib ``ax`` (``fig`` for several panels) or
on a new Figure, and returns the Figure; nothing is written until :func:`save_figure`. The
animations write an MP4 (with ffmpeg) or a GIF. The physics layers never import matplotlib.
"""

from typing import TYPE_CHECKING

from .._lazy import lazy_package

if TYPE_CHECKING:  # the names, as the type checker sees them; each is imported on its first use
    from ._backend import save_figure
    from .animate import (
        animate_body_frame,
        animate_ground_frame,
        animation_path,
        ffmpeg_path,
    )
    from .control import (
        control_figures,
        figure_attitude_error,
        figure_body_rates,
        figure_dipole,
        figure_momentum_budget,
        figure_wheels,
    )
    from .fit import figure_fit, figure_recording
    from .gravity import figure_gravity_stability
    from .knowledge import figure_knowledge
    from .maps import figure_stability_map, figure_sweep
    from .montecarlo import figure_detumble_mc
    from .notebook import show
    from .phase import (
        PHASE_PORTRAITS,
        figure_herpolhode,
        figure_polhode,
        phase_portrait_problem,
        polhode_family,
        separatrices,
    )
    from .plots import AliasedSamplesWarning, envelope, figure_drift, figure_omega, figure_omega_grid, plot_omega, sample_phase
    from .scene import body_lines, body_size, part_lines
    from .spacecraft import (
        figure_energy,
        figure_nutation,
        figure_omega_panels,
        figure_orbit_angles,
        spacecraft_figures,
    )
    from .tensor import figure_tensor

lazy_package(__name__)

__all__ = [
    "PHASE_PORTRAITS",
    "AliasedSamplesWarning",
    "animate_body_frame",
    "animate_ground_frame",
    "animation_path",
    "body_lines",
    "body_size",
    "control_figures",
    "envelope",
    "ffmpeg_path",
    "figure_attitude_error",
    "figure_body_rates",
    "figure_detumble_mc",
    "figure_dipole",
    "figure_drift",
    "figure_energy",
    "figure_fit",
    "figure_gravity_stability",
    "figure_herpolhode",
    "figure_knowledge",
    "figure_momentum_budget",
    "figure_nutation",
    "figure_omega",
    "figure_omega_grid",
    "figure_omega_panels",
    "figure_orbit_angles",
    "figure_polhode",
    "figure_recording",
    "figure_stability_map",
    "figure_sweep",
    "figure_tensor",
    "figure_wheels",
    "part_lines",
    "phase_portrait_problem",
    "plot_omega",
    "polhode_family",
    "sample_phase",
    "save_figure",
    "separatrices",
    "show",
    "spacecraft_figures",
]
