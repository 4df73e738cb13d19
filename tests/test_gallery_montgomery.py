"""Gallery entry: Montgomery's rotation per period, closed form against DOP853 on seven bodies."""

from __future__ import annotations

import numpy as np

import tumble
from gallery import Entry, body, code, magnitude, page_test, sig
from tumble.analysis import montgomery_angle, period, polhode_solid_angle, rotation_per_period


MONTGOMERY_BODIES = [
    ("book-like, SAM", [1.0, 2.0, 3.0], [0.2, 0.3, 1.0]),
    ("book-like, SAM near the separatrix", [1.0, 2.0, 3.0], [0.1, 1.0, 0.3]),
    ("book-like, LAM", [1.0, 2.0, 3.0], [1.0, 0.5, 0.1]),
    ("flat plate, LAM", [2.0, 2.5, 4.5], [0.7, -0.2, 0.05]),
    ("seed T-handle, SAM", [0.125, 0.3125, 0.4375], [0.1, 10.0, 0.1]),
    ("seed T-handle, LAM", [0.125, 0.3125, 0.4375], [-0.3, 10.0, 0.1]),
    ("oblate top", [2.0, 2.0, 3.0], [0.3, 0.0, 1.0]),
]


def compute_montgomery():
    rows = []
    for name, moments, omega0 in MONTGOMERY_BODIES:
        T = float(period(omega0, moments))
        traj = tumble.simulate(body(moments), omega0, times=[0.0, T], method="dop853")
        closed = float(montgomery_angle(omega0, moments))
        measured = rotation_per_period(traj)
        diff = (measured - closed + np.pi) % (2 * np.pi) - np.pi
        rows.append({"name": name, "moments": moments, "omega0": omega0, "T": T,
                     "Omega": float(polhode_solid_angle(omega0, moments)), "closed": closed,
                     "measured": measured, "diff": diff})
    return {"rows": rows, "tolerance": 1e-10}  # measured: < 1e-11 rad


def _montgomery_page(r: dict) -> str:
    rows = "\n".join(
        f"| {x['name']} | {x['moments']} | {x['omega0']} | {sig(x['T'], 7)} | {sig(x['Omega'], 7)} | "
        f"{sig(x['closed'], 9)} | {sig(x['measured'], 9)} | {magnitude(x['diff'])} |"
        for x in r["rows"])
    return f"""# Montgomery's rotation per period

**Published formula.** R. Montgomery, "How much does the rigid body rotate? A Berry's phase from
the 18th century", Am. J. Phys. 59 (1991) 394: after one period `T` of its body-frame motion a
free rigid body has turned about its angular momentum by

    Delta theta = 2 E T / |L| - Omega   (mod 2 pi),

`Omega` the solid angle enclosed by the path of `L / |L|` in the body.

**tumble's closed form.** `tumble.analysis.montgomery_angle` evaluates it through the exact
solution: `Delta theta = Delta phi mod 2 pi`, with the precession per period
`Delta phi = |L| T / I_r + 4 |L| (I_r - I_o) Pi(n | m) / (I1 I3 p)` (the complete elliptic
integral of the third kind; derivation in `tumble.analysis.periods`). There `I_r` is the extreme
moment about whose axis `L` circulates (`I3` where `|L|^2 > 2 E I2`, else `I1`), `I_o` the other
extreme moment, `m` and `p` the parameter and rate of the Jacobi functions of the motion
(`omega_2 ~ sn(p t | m)`, `T = 4 K(m) / p`), and `n = -I_r (I2 - I_o) / (I_o (I_r - I2))`.
`Delta theta` counts positive as a right-handed turn about `L_world`. `Omega` is
`polhode_solid_angle` (oriented: positive for circulation about the major axis, negative about
the minor axis), held against an mpmath quadrature of the polhode in `tests/test_periods.py`.

**Conditions.** Each body spun from `omega0` (principal frame, rad/s), simulated by DOP853 (rtol
1e-12) to `T`; *measured* is the angle of `R(T) R(0)^-1` about `L_world`
(`tumble.analysis.rotation_per_period`). Tolerance {r['tolerance']:g} rad.

| body | moments (kg m^2) | omega0 (rad/s) | T (s) | Omega (sr) | Delta theta, closed form (rad) | measured (rad) | difference (rad) |
|---|---|---|---|---|---|---|---|
{rows}

{code(compute_montgomery)}"""


ENTRY = Entry(
    slug="montgomery-phase",
    title="Montgomery's rotation per period, closed form vs DOP853, seven bodies",
    order=20,
    compute=compute_montgomery,
    page=_montgomery_page,
)
test_page_is_current = page_test(ENTRY)


def test_montgomery_closed_form_matches_the_measured_rotation():
    r = ENTRY.result()
    for row in r["rows"]:
        assert abs(row["diff"]) < r["tolerance"], row["name"]


def _euler_and_attitude(_t, y, I):
    """Euler's equations and R' = R [omega]x, written here (not tumble's): y = (omega, R row-major)."""
    w, R = y[:3], y[3:].reshape(3, 3)
    dw = np.array([(I[1] - I[2]) * w[1] * w[2] / I[0], (I[2] - I[0]) * w[2] * w[0] / I[1],
                   (I[0] - I[1]) * w[0] * w[1] / I[2]])
    cross = np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])
    return np.r_[dw, (R @ cross).ravel()]


def test_an_independent_integration_turns_each_body_by_the_closed_form():
    """scipy's DOP853 on Euler's equations and the attitude written above, started at R = 1 (so
    L_world = L_body(0)): after one period T the rotation R(T) is about L_world, by the page's
    closed form (mod 2 pi); and the closed form is Montgomery's ``2 E T / |L| - Omega``."""
    from scipy.integrate import solve_ivp
    from scipy.spatial.transform import Rotation

    for row in ENTRY.result()["rows"]:
        I, w0 = np.array(row["moments"]), np.array(row["omega0"])
        sol = solve_ivp(_euler_and_attitude, (0.0, row["T"]), np.r_[w0, np.eye(3).ravel()], method="DOP853",
                        rtol=1e-12, atol=1e-14, args=(I,))
        R = Rotation.from_matrix(sol.y[3:, -1].reshape(3, 3))
        L = I * w0
        rotvec = R.as_rotvec()
        assert np.linalg.norm(np.cross(rotvec, L)) <= 1e-8 * np.linalg.norm(L), row["name"]  # about L
        angle = np.sign(rotvec @ L) * np.linalg.norm(rotvec)
        assert abs((angle - row["closed"] + np.pi) % (2 * np.pi) - np.pi) < 1e-8, row["name"]
        montgomery = 2 * (0.5 * I @ w0**2) * row["T"] / np.linalg.norm(L) - row["Omega"]
        assert abs((montgomery - row["closed"] + np.pi) % (2 * np.pi) - np.pi) < 1e-10, row["name"]
