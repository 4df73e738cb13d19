"""Figures: the geometry they draw is the physics (polhodes, separatrices, herpolhode)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import tumble
from tumble.cli import main
from tumble.viz import body_lines, polhode_family, separatrices

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
I = np.array([0.125, 0.3125, 0.4375])


def test_polhodes_lie_on_the_sphere_and_keep_their_energy():
    R = 3.0
    for L in polhode_family(I, R):
        np.testing.assert_allclose(np.linalg.norm(L, axis=1), R, rtol=1e-12)
        E = 0.5 * np.sum(L**2 / I, axis=1)
        np.testing.assert_allclose(E, E[0], rtol=1e-12)
        # each closed curve stays on one side of the separatrix energy |L|^2 / (2 I2)
        assert np.all(E > R**2 / (2 * I[1])) or np.all(E < R**2 / (2 * I[1]))
        np.testing.assert_allclose(L[-1], L[0], atol=1e-9 * R)  # one whole period


def test_separatrices_have_the_intermediate_energy_and_pass_through_its_axis():
    R = 2.0
    for C in separatrices(I, R):
        np.testing.assert_allclose(np.linalg.norm(C, axis=1), R, rtol=1e-12)
        np.testing.assert_allclose(0.5 * np.sum(C**2 / I, axis=1), R**2 / (2 * I[1]), rtol=1e-12)
        assert np.min(np.linalg.norm(C - [0, R, 0], axis=1)) < 1e-9


def test_a_simulated_intermediate_spin_runs_along_the_separatrix():
    """Its L stays (to the size of the perturbation) in one of the two separatrix planes."""
    traj = tumble.simulate(tumble.t_handle(), [1e-4, 5.0, 1e-4], t_end=10.0)
    R = traj.angular_momentum_norm[0]
    C1, C2 = separatrices(I, R)
    normals = [np.cross(C[0], C[90]) / R**2 for C in (C1, C2)]  # planes of the two great circles
    off = np.min([np.abs(traj.angular_momentum @ n) for n in normals], axis=0)
    assert np.max(off) < 1e-3 * R


def test_herpolhode_plane_is_invariable():
    traj = tumble.simulate(tumble.iss_t_handle(), [1.0, 8.0, -2.0], t_end=5.0, samples=400)
    n = traj.angular_momentum_world[0] / traj.angular_momentum_norm[0]
    height = traj.omega_world @ n
    np.testing.assert_allclose(height, 2 * traj.energy[0] / traj.angular_momentum_norm[0], rtol=1e-12)


def test_scene_is_drawn_from_the_parts():
    body = tumble.load_body(EXAMPLES / "bodies" / "every_part.toml")
    lines = body_lines(body)
    assert any(removed for _, removed in lines)  # the hole is drawn, marked as removed
    pts = np.concatenate([p for p, _ in lines])
    assert np.all(np.isfinite(pts))
    rod = body_lines(tumble.Body([tumble.Rod(mass=1.0, length=2.0, axis=(1, 0, 0)), tumble.PointMass(mass=1.0, center=(0, 1, 0))]))
    np.testing.assert_allclose(rod[0][0], [[-1, -0.5, 0], [1, -0.5, 0]], atol=1e-15)  # about the COM


def test_plot_command_writes_every_figure(tmp_path, capsys):
    assert main(["plot", str(EXAMPLES / "seed_flip.toml"), "--out", str(tmp_path), "--format", "png", "svg"]) == 0
    for name in ("omega", "polhode", "herpolhode", "drift"):
        for fmt in ("png", "svg"):
            assert (tmp_path / f"{name}.{fmt}").stat().st_size > 5_000
    assert not list(tmp_path.glob(".*"))


@pytest.mark.parametrize("command", ["inertia", "simulate", "plot", "view", "demo"])
def test_every_subcommand_has_help_with_an_example(command, capsys):
    with pytest.raises(SystemExit) as info:
        main([command, "--help"])
    assert info.value.code == 0
    assert "Example" in capsys.readouterr().out
