"""The gallery (docs/gallery/): published numbers that tumble reproduces, generated and checked here.

Each entry computes its quantities with tumble (``compute_<entry>``), compares them with the
published value within the published range or tolerance, and ``render(entry)`` writes its page:
the published quantity, its source, the conditions, tumble's value, the difference and the code
that made it (the source of the compute function, pasted verbatim). ``test_page_is_current``
rewrites a page only when its text changed, and then fails, so a stale committed page fails the
suite; run the test again (or commit the rewritten page) to pass.

Numbers on the pages are rounded so that they do not depend on the last bits of a platform's
arithmetic: values to 9 significant digits, differences to their power of ten.
"""

from __future__ import annotations

import functools
import inspect
import math
import textwrap
from pathlib import Path

import numpy as np
import pytest

import tumble
from tumble.analysis import (
    flip_interval,
    flip_times,
    montgomery_angle,
    period,
    polhode_solid_angle,
    rotation_per_period,
    symmetric_top_rates,
)

GALLERY = Path(__file__).resolve().parents[1] / "docs" / "gallery"


def body(moments):
    """A body with these principal moments (kg m^2) along the design axes."""
    I = np.asarray(moments, float)
    return tumble.MassProperties(1.0, np.zeros(3), np.diag(I), I.copy(), np.eye(3))


def upward_crossings(t, y):
    """Times of upward zero crossings of a sampled component, linearly interpolated, s."""
    k = np.flatnonzero((y[:-1] < 0) & (y[1:] >= 0))
    return t[k] - y[k] * (t[k + 1] - t[k]) / (y[k + 1] - y[k])


# --- Earth's free (Eulerian) nutation ------------------------------------------------------------

#: Dynamical flattening ``H = (C - A) / C`` of the Earth: 3273795e-9, uncertainty 1e-9 (IERS
#: Conventions (2010), G. Petit & B. Luzum (eds.), IERS Technical Note 36, Table 1.1, as quoted
#: with that citation by a public constants table; the primary table itself was not read here).
EARTH_H = 3273795e-9
EARTH_H_UNCERTAINTY = 1e-9
#: Nominal mean angular velocity of the Earth, rad/s (IERS Conventions (2010), Table 1.1; NOT
#: verified here). It only sets the time unit: the period in sidereal days, ``T w / (2 pi)``,
#: does not depend on it.
EARTH_OMEGA = 7.292115e-5


def compute_earth():
    H, w = EARTH_H, EARTH_OMEGA
    moments = [1.0 - H, 1.0 - H, 1.0]  # A = B = (1 - H) C with C = 1 kg m^2: only ratios matter
    omega0 = [1e-6 * w, 0.0, w]  # a small wobble about the figure axis
    day = 2 * np.pi / w  # one sidereal day (one turn of the Earth), s
    closed_form = (1.0 - H) / H  # A / (C - A), sidereal days (Landau & Lifshitz sec. 33)
    _, body_rate = symmetric_top_rates(omega0, moments)  # (C - A) w3 / A, rad/s
    traj = tumble.simulate(body(moments), omega0, t_end=2.2 * closed_form * day, samples=40001, method="dop853")
    up = upward_crossings(traj.t, traj.omega[:, 0])  # the wobble of omega in the body
    measured = float(np.mean(np.diff(up))) / day
    return {
        "closed_form": closed_form,
        "rates": 2 * np.pi / float(body_rate) / day,
        "measured": measured,
        "tolerance": EARTH_H_UNCERTAINTY / H**2,  # d/dH (1 - H) / H: the published range of H
    }


# --- Montgomery's rotation per period ----------------------------------------------------------

MONTGOMERY_BODIES = [
    ("book-like, SAM", [1.0, 2.0, 3.0], [0.2, 0.3, 1.0]),
    ("book-like, SAM near the separatrix", [1.0, 2.0, 3.0], [0.1, 1.0, 0.3]),
    ("book-like, LAM", [1.0, 2.0, 3.0], [1.0, 0.5, 0.1]),
    ("flat plate, LAM", [2.0, 2.5, 7.0], [0.7, -0.2, 0.05]),
    ("seed T-handle, SAM", [0.125, 0.3125, 0.4375], [0.1, 10.0, 0.1]),
    ("seed T-handle, LAM", [0.125, 0.3125, 0.4375], [-0.3, 10.0, 0.1]),
    ("oblate top", [1.0, 1.0, 3.0], [0.3, 0.0, 1.0]),
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
    return {"rows": rows, "tolerance": 1e-8}


# --- The T-handle's flip period (internal consistency) -----------------------------------------

def compute_t_handle():
    handle = tumble.t_handle()  # the seed's T-handle: moments 0.125, 0.3125, 0.4375 kg m^2
    omega0 = [0.1, 10.0, 0.1]  # 10 rad/s about the intermediate axis, 0.1 rad/s on the others
    closed = float(flip_interval(omega0, handle.principal_moments))
    traj = tumble.simulate(handle, omega0, t_end=10.5 * closed, samples=100001, method="dop853")
    flips = flip_times(traj.t, traj.omega[:, 1])
    measured = float(np.mean(np.diff(flips)))
    return {"moments": handle.principal_moments.tolist(), "closed": closed, "measured": measured,
            "flips": len(flips), "tolerance": 1e-10}


ENTRIES = {
    "earth-free-nutation": compute_earth,
    "montgomery-phase": compute_montgomery,
    "t-handle-flip": compute_t_handle,
}


@functools.cache
def result(entry: str) -> dict:
    return ENTRIES[entry]()


def sig(x: float, digits: int = 9) -> str:
    return f"{x:.{digits}g}"


def magnitude(d: float) -> str:
    """A difference as the power of ten just above it (stable across platforms)."""
    d = abs(d)
    return "0" if d == 0 else f"< 1e{math.floor(math.log10(d)) + 1}"


def code(*functions) -> str:
    return "```python\n" + "\n\n".join(textwrap.dedent(inspect.getsource(f)).rstrip() for f in functions) + "\n```\n"


def _earth_page(r: dict) -> str:
    return f"""# Earth's free (Eulerian) nutation

**Published quantity.** The Earth's dynamical flattening `H = (C - A) / C = 3273795e-9`
(uncertainty 1e-9): IERS Conventions (2010), G. Petit & B. Luzum (eds.), IERS Technical Note
No. 36, Table 1.1. *Verification:* the value and its uncertainty were checked against a public
constants table that quotes them with this citation; the primary table was not read here.

**What it predicts.** A rigid, axially symmetric Earth (`A = B < C`) spinning at `w` about its
figure axis, slightly off it, wobbles in the body at `(C - A) w / A` (Landau & Lifshitz,
*Mechanics*, sec. 33): the period is `A / (C - A) = (1 - H) / H` sidereal days, the Eulerian
free nutation. The published uncertainty of `H` gives a range of
±{sig(r['tolerance'], 2)} sidereal days.

**Conditions.** Moments `A = B = 1 - H`, `C = 1` (kg m^2; only ratios matter); spin
`w = {EARTH_OMEGA}` rad/s (nominal, IERS Conventions (2010) Table 1.1, *not verified here*; the
result in sidereal days does not depend on it); wobble `omega_1 = 1e-6 w`; DOP853 over 2.2
periods, 40001 samples; the period is the mean interval between upward zero crossings of
`omega_1`.

| | sidereal days |
|---|---|
| `(1 - H) / H` from the published `H` | {sig(r['closed_form'])} |
| tumble, `symmetric_top_rates` | {sig(r['rates'])} |
| tumble, DOP853 run (measured) | {sig(r['measured'])} |
| difference, measured - closed form | {magnitude(r['measured'] - r['closed_form'])} |
| published range (from the uncertainty of `H`) | ±{sig(r['tolerance'], 2)} |

**Why the observed Chandler wobble is longer.** The wobble observed in the Earth's polar
motion, the Chandler wobble, has a period of about 433 days (Encyclopaedia Britannica,
"Chandler Wobble"), not ~305: the Earth is not rigid, and its elastic deformation lengthens the
period (Love and Larmor, as summarised by O. Portilho, arXiv:0809.4506, sec. I).
*Verification:* only the passages of these two sources quoted here were read; the primary
literature (e.g. Munk & MacDonald 1960, Gross 2007) was not, and the part played by the oceans
and the fluid core is not claimed here. tumble models a rigid body and reproduces the Eulerian
period only.

**Code** (`tests/test_gallery.py`):

{code(compute_earth)}"""


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
integral of the third kind; derivation in `tumble.analysis.periods`); `Omega` is
`polhode_solid_angle` (oriented: positive for circulation about the major axis, negative about
the minor axis), held against an mpmath quadrature of the polhode in `tests/test_periods.py`.

**Conditions.** Each body spun from `omega0` (principal frame, rad/s), simulated by DOP853 (rtol
1e-12) to `T`; *measured* is the angle of `R(T) R(0)^-1` about `L_world`
(`tumble.analysis.rotation_per_period`). Tolerance {r['tolerance']:g} rad.

| body | moments (kg m^2) | omega0 (rad/s) | T (s) | Omega (sr) | Delta theta, closed form (rad) | measured (rad) | difference (rad) |
|---|---|---|---|---|---|---|---|
{rows}

**Code** (`tests/test_gallery.py`):

{code(compute_montgomery)}"""


def _t_handle_page(r: dict) -> str:
    return f"""# The T-handle's flip period (internal consistency)

*An internal consistency entry: tumble's simulation against tumble's closed form, no published
number.* (Peterson & Schwalm, Am. J. Phys. 89 (2021) 349, treat the same effect; their numbers
were not verified here and are not used.)

**Quantity.** The interval between flips of the seed's T-handle (`tumble.t_handle()`, principal
moments {r['moments']} kg m^2) spun at 10 rad/s about its intermediate axis with 0.1 rad/s about
each of the others: `omega0 = [0.1, 10, 0.1]` rad/s (principal frame). Closed form
`2 K(m) / p` (Landau & Lifshitz, *Mechanics*, sec. 37; `tumble.analysis.flip_interval`).

**Conditions.** DOP853 (rtol 1e-12) over 10.5 closed-form intervals, 100001 samples; measured:
the mean interval between the sign changes of `omega_2` ({r['flips']} flips, linearly
interpolated). Tolerance {r['tolerance']:g} relative.

| | s |
|---|---|
| closed form, `flip_interval` | {sig(r['closed'])} |
| measured, DOP853 | {sig(r['measured'])} |
| relative difference | {magnitude(r['measured'] / r['closed'] - 1)} |

**Code** (`tests/test_gallery.py`):

{code(compute_t_handle)}"""


PAGES = {"earth-free-nutation": _earth_page, "montgomery-phase": _montgomery_page, "t-handle-flip": _t_handle_page}

TITLES = {
    "earth-free-nutation": "Earth's free (Eulerian) nutation from the IERS dynamical flattening",
    "montgomery-phase": "Montgomery's rotation per period, closed form vs DOP853, seven bodies",
    "t-handle-flip": "The T-handle's flip period (internal consistency)",
}


def render(entry: str) -> str:
    """The Markdown text of a gallery page (``"index"`` for the list of entries)."""
    if entry == "index":
        items = "\n".join(f"- [{TITLES[e]}]({e}.md)" for e in ENTRIES)
        return f"""# Gallery: published numbers tumble reproduces

Each page gives a published quantity, its source, the conditions, tumble's value, the
difference and the code that makes it. The pages are generated and checked by
`tests/test_gallery.py`: a page that no longer matches what the code computes fails the test
suite (the test rewrites it).

{items}

Not included: tumbling asteroids ((99942) Apophis, Pravec et al., Icarus 233 (2014) 48;
(4179) Toutatis, Hudson & Ostro, Science 270 (1995) 84). Their periods and moment ratios
could not be verified from the papers here, so no entry uses them;
`tumble.analysis.npa_periods` computes such periods from moments and omega.
"""
    return PAGES[entry](result(entry))


@pytest.mark.parametrize("entry", ["index", *ENTRIES])
def test_page_is_current(entry):
    """The committed page equals the rendered text; a stale page is rewritten and fails."""
    path = GALLERY / f"{entry}.md"
    text = render(entry)
    old = path.read_text() if path.exists() else None
    if old != text:
        GALLERY.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    assert old == text, f"{path} was stale and has been rewritten: review and commit it"


def test_earth_free_nutation_within_the_published_range():
    r = result("earth-free-nutation")
    assert abs(r["measured"] - r["closed_form"]) <= r["tolerance"]  # measured difference: see the page
    assert r["measured"] == pytest.approx(r["closed_form"], rel=1e-12)  # measured: < 1e-11 days, 3e-14 relative
    assert r["rates"] == pytest.approx(r["closed_form"], rel=1e-12)
    assert 300 < r["measured"] < 310  # the ~305-day Eulerian period, not the 433-day Chandler wobble


def test_montgomery_closed_form_matches_the_measured_rotation():
    r = result("montgomery-phase")
    for row in r["rows"]:
        assert abs(row["diff"]) < r["tolerance"], row["name"]


def test_t_handle_flip_period_matches_the_closed_form():
    r = result("t-handle-flip")
    assert r["flips"] >= 10
    assert r["measured"] == pytest.approx(r["closed"], rel=r["tolerance"])
