"""Gallery entry: the tumbling asteroids (4179) Toutatis and (99942) Apophis, their periods and modes."""

from __future__ import annotations

import numpy as np

import tumble
from gallery import Entry, body, code, page_test, sig
from tumble.analysis import axis_precession_period, npa_periods_measured, periods_consistent

DAY, HOUR = 86400.0, 3600.0

#: Toutatis's "dimensions along the principal axes are 1.92, 2.40, and 4.60 kilometers" and it
#: rotates "in a long-axis mode characterized by periods of 5.41 days (rotation about the long
#: axis) and 7.35 days (average for long-axis precession)"; "to within the model's uncertainties,
#: Toutatis's density is homogeneous": R. S. Hudson & S. J. Ostro, Science 270 (1995) 84,
#: abstract (read on the journal's page; the paper's moment ratios were not read). Semi-axes, m.
TOUTATIS_SEMI_AXES = (2300.0, 1200.0, 960.0)
#: (source, P_phi, P_psi, uncertainty), days. Zhao, Hu & Ji, "Revisit of rotational dynamics of
#: asteroid 4179 Toutatis from Chang'e-2's flyby", IAU Symp. 318, arXiv:1511.04357, abstract:
#: "5.38±0.03 days for rotation about the long axis and 7.40±0.03 days for precession of the long
#: axis about the angular momentum vector". Hudson & Ostro give no uncertainty in the abstract:
#: half a unit of their last digit is used.
TOUTATIS_PERIODS = (("Hudson & Ostro 1995", 7.35, 5.41, 0.005), ("Zhao et al. 2015", 7.40, 5.38, 0.03))

#: Apophis, H.-J. Lee et al., A&A 661 (2022) L3, abstract (read on a public abstract page): "a
#: short axis mode with rotation and precession periods of 264.178 hours and 27.38547 hours" and
#: moments "I_a:I_b:I_c=0.64:0.97:1" (no uncertainties in the abstract).
APOPHIS_RATIOS = (0.64, 0.97)
#: (source, P_phi, P_psi), hours.
APOPHIS_PERIODS = (("Lee et al. 2022", 27.38547, 264.178), ("Pravec et al. 2014", 27.38, 263.0))
#: P. Pravec et al., "The tumbling spin state of (99942) Apophis", Icarus 233 (2014) 48, abstract
#: (read in a public transcription): SAM with "E/E0 = 1.024 ± 0.013 (All quoted uncertainties
#: correspond to 3σ)". Its periods, "precession period: 27.38±0.07 h", "rotation period: 263±6 h"
#: and "period of harmonic with strongest lightcurve amplitude: 30.56±0.01 h", were read in a
#: copy of Wikipedia's article citing the paper (secondary; the paper's tables were not read).
APOPHIS_ENERGY = (1.024, 0.013)
APOPHIS_UNCERTAINTY = (0.07, 6.0)
APOPHIS_P1 = (30.56, 0.01)


def motion(family, row):
    """The angular velocity (principal frame, rad/s) of one row of a :class:`PeriodFamily`.

    Its parametrisation (``periods_consistent``'s Notes): at ``|L| = I3 = 1``, ``omega = (sin b /
    x, 0, cos b)`` with ``x = I1/I3`` and energy ``2 E I3 / |L|^2 = sin^2 b / x + cos^2 b``.
    """
    x = family.ratios[row, 0]
    b = np.arcsin(np.sqrt((family.energy[row] - 1.0) / (1.0 / x - 1.0)))
    return family.L_over_I3[row] * np.array([np.sin(b) / x, 0.0, np.cos(b)])


def compute_toutatis():
    toutatis = tumble.Body([tumble.Ellipsoid(semi_axes=TOUTATIS_SEMI_AXES, density=1.0)])
    ratios = toutatis.principal_moments[:2] / toutatis.principal_moments[2]
    rows = []
    for source, P_phi, P_psi, tol in TOUTATIS_PERIODS:
        fam = periods_consistent(P_phi * DAY, P_psi * DAY, ratios=[ratios])
        for i in range(len(fam.mode)):
            w = motion(fam, i)
            traj = tumble.simulate(toutatis, w, t_end=6 * P_psi * DAY, samples=20001, method="dop853")
            m_phi, m_psi, m_mode = npa_periods_measured(traj)
            rows.append({"source": source, "P_phi": P_phi, "P_psi": P_psi, "tol": tol, "mode": str(fam.mode[i]),
                         "energy": float(fam.energy[i]), "measured_mode": m_mode,
                         "phi": m_phi / DAY, "psi": m_psi / DAY})
    grid = periods_consistent(7.40 * DAY, 5.38 * DAY)
    return {"ratios": ratios.tolist(), "rows": rows, "grid_modes": sorted(set(grid.mode.tolist())),
            "grid_count": len(grid.mode), "grid_min": grid.ratios.min(axis=0).tolist(),
            "grid_max": grid.ratios.max(axis=0).tolist()}


def compute_apophis():
    rows = []
    for source, P_phi, P_psi in APOPHIS_PERIODS:
        # P_phi read as the short axis's precession (tumble's SAM P_phi) or as the long axis's:
        # in SAM the long axis turns about L once per P_psi less than the short axis does.
        for reading, short_axis in (("short axis", P_phi), ("long axis", 1 / (1 / P_phi + 1 / P_psi))):
            fam = periods_consistent(short_axis * HOUR, P_psi * HOUR, ratios=[APOPHIS_RATIOS])
            sam = int(np.flatnonzero(fam.mode == "SAM")[0])
            traj = tumble.simulate(body([*APOPHIS_RATIOS, 1.0]), motion(fam, sam), t_end=3 * P_psi * HOUR,
                                   samples=30001, method="dop853")
            m_phi, m_psi, m_mode = npa_periods_measured(traj)
            rows.append({"source": source, "reading": reading, "P_phi": P_phi, "P_psi": P_psi,
                         "modes": sorted(fam.mode.tolist()), "energy": float(fam.energy[sam]),
                         "measured_mode": m_mode, "psi": m_psi / HOUR, "short": m_phi / HOUR,
                         "short_axis3": axis_precession_period(traj, 3) / HOUR, "long": axis_precession_period(traj, 1) / HOUR})
    return {"rows": rows}


def compute_asteroids():
    return {"toutatis": compute_toutatis(), "apophis": compute_apophis()}


def _toutatis_rows(t: dict) -> str:
    return "\n".join(
        f"| {x['source']} | {x['P_phi']} | {x['P_psi']} | ±{x['tol']} | {x['mode']} | {sig(x['energy'], 6)} "
        f"| {sig(x['phi'], 7)} | {sig(x['psi'], 7)} |" for x in t["rows"])


def _apophis_rows(a: dict) -> str:
    return "\n".join(
        f"| {x['source']} | {x['P_phi']} | {x['P_psi']} | {x['reading']} | {', '.join(x['modes'])} "
        f"| {sig(x['energy'], 6)} | {sig(x['psi'], 6)} | {sig(x['long'], 6)} | {sig(x['short'], 6)} |"
        for x in a["rows"])


def _asteroids_page(r: dict) -> str:
    t, a = r["toutatis"], r["apophis"]
    e, de = APOPHIS_ENERGY
    return f"""# Tumbling asteroids: (4179) Toutatis and (99942) Apophis

A tumbling (non-principal-axis) asteroid shows two periods: `P_psi`, the period of its motion in
the body frame (the rotation about the axis it circulates about, and the nutation), and `P_phi`,
a mean precession period about the angular momentum L. tumble computes both from the moments and
omega (`tumble.analysis.npa_periods`, closed form from the exact solution; measured on a run by
`npa_periods_measured`) and inverts them: `tumble.analysis.periods_consistent` gives the moment
ratios, energies and momenta consistent with a pair of periods. **The inverse is not unique**: two
periods fix two of the four numbers of a free motion (`I1/I3`, `I2/I3`, the energy
`2 E I3 / |L|^2 = E/E0` and `|L|`), so the ratios must come from a shape model.

## (4179) Toutatis, long-axis mode (LAM)

**Published.** R. S. Hudson & S. J. Ostro, "Shape and non-principal axis spin state of asteroid
4179 Toutatis", Science 270 (1995) 84, abstract: "a long-axis mode characterized by periods of
5.41 days (rotation about the long axis) and 7.35 days (average for long-axis precession)";
dimensions "along the principal axes" 1.92, 2.40 and 4.60 km; density homogeneous to within the
model's uncertainties. Y. Zhao, S. Hu & J. Ji, "Revisit of rotational dynamics of asteroid 4179
Toutatis from Chang'e-2's flyby", IAU Symposium 318, arXiv:1511.04357, abstract: "5.38±0.03 days
for rotation about the long axis and 7.40±0.03 days for precession of the long axis about the
angular momentum vector". *Verification:* these abstracts were read (on the journal's page and
on public arXiv listings); the papers' moment ratios and energies were not, and are not used.

**Conventions.** In LAM tumble's `P_psi` is the rotation about the long axis (the circulation
axis) and `P_phi` the mean precession of the long axis about L: the definitions in the two
abstracts' own words.

**Model and conditions.** A homogeneous ellipsoid (`tumble.Ellipsoid`) with semi-axes half the
published dimensions, {TOUTATIS_SEMI_AXES} m: `I1/I3 = {sig(t['ratios'][0], 6)}`,
`I2/I3 = {sig(t['ratios'][1], 6)}`. This is tumble's model, not the published moment ratios (the
extents of an irregular shape are not the semi-axes of its dynamically equivalent ellipsoid).
Hudson & Ostro's abstract gives no uncertainty: half a unit of their last digit is used. For
each published pair,
`periods_consistent` solves for the energy and `|L|` at these ratios; the motion found is run by
DOP853 (rtol 1e-12) over 6 `P_psi`, 20001 samples, and its periods measured by
`npa_periods_measured`.

| source | published `P_phi` (d) | published `P_psi` (d) | uncertainty (d) | mode found | `E/E0` | measured `P_phi` (d) | measured `P_psi` (d) |
|---|---|---|---|---|---|---|---|
{_toutatis_rows(t)}

At the ellipsoid's ratios each published pair has exactly one solution, in LAM, the published
mode. The run of that solution gives both periods back within the published uncertainty: a
round trip, which checks the solve and the measurement of the periods, not the model (the
periods went in). What the periods tell is the mode, and that at these ratios it is the only
solution. Over the whole triangle
of physical bodies (`periods_consistent`'s default grid, Zhao et al.'s pair) there are
{t['grid_count']} solutions, all in {', '.join(t['grid_modes'])}, with `I1/I3` from
{sig(t['grid_min'][0], 3)} to {sig(t['grid_max'][0], 3)} and `I2/I3` from
{sig(t['grid_min'][1], 3)} to {sig(t['grid_max'][1], 3)}: the periods alone do not fix the
shape.

## (99942) Apophis, short-axis mode (SAM)

**Published.** H.-J. Lee et al., "Refinement of the convex shape model and tumbling spin state of
(99942) Apophis using the 2020-2021 apparition data", A&A 661 (2022) L3, abstract: "a short axis
mode with rotation and precession periods of 264.178 hours and 27.38547 hours", "I_a:I_b:I_c =
0.64:0.97:1". P. Pravec et al., "The tumbling spin state of (99942) Apophis", Icarus 233 (2014)
48, abstract: SAM with `E/E0 = {e} ± {de}` (3σ); its periods `P_phi = 27.38 ± 0.07` h
(precession), `P_psi = 263 ± 6` h (rotation) and the period of the strongest light-curve
harmonic `P1 = 30.56 ± 0.01` h. *Verification:* Lee et al.'s abstract and Pravec et al.'s
abstract were read (public copies); Pravec et al.'s three periods were read only in a copy of
Wikipedia's article that cites the paper (secondary); J. Ďurech et al., EPSC2024-257 (abstract),
gives the same two, "263 h and 27.38 h", for rotation and precession.

**Which axis's precession is `P_phi`?** In SAM tumble's `P_phi` is the mean precession of the
*short* axis, the axis the body circulates about (`npa_periods`); the long axis turns about L
once per `P_psi` less often. The definitions used by the papers (Samarasinha & A'Hearn 1991;
Kaasalainen 2001; Pravec et al. 2005) were not read here, so both readings are computed: the
published `P_phi` as the short axis's precession (tumble's `P_phi`), and as the long axis's.

**Conditions.** Lee et al.'s ratios `I1/I3 = 0.64`, `I2/I3 = 0.97`; for each source and reading,
`periods_consistent` solves for the energy (the SAM solution is kept) and `|L|`; the motion is
run by DOP853 over 3 `P_psi`, 30001 samples. Measured: `P_psi` and the short axis's period by
`npa_periods_measured`, the long axis's by the same azimuth method (`tumble.analysis.axis_precession_period`).

| source | `P_phi` (h) | `P_psi` (h) | `P_phi` read as | modes found | SAM `E/E0` | measured `P_psi` (h) | long axis (h) | short axis (h) |
|---|---|---|---|---|---|---|---|---|
{_apophis_rows(a)}

**Result.** Under both readings Lee et al.'s ratios admit a SAM motion with both published
periods, and its energy lies in Pravec et al.'s range `E/E0 = {e} ± {de}` (from another data set;
both readings fit, so the energy does not decide). Pravec et al.'s own three periods do decide:
read as the short axis's precession, their `P_phi` and `P_psi` give a long axis turning every
30.56 h, their strongest light-curve harmonic `P1` (as expected if the light curve follows the
elongated body's long axis); read as the long axis's, they give no period near 30.56 h. So the
published SAM `P_phi` is the short axis's precession period (`2 pi T / Delta phi`, `T = P_psi`
and `Delta phi` from `tumble.analysis.precession_per_period`), which is what tumble's
`npa_periods` and `periods_consistent` take as `P_phi`. (This rests on the numbers, not on a
definition read in the papers.)

{code(motion, compute_toutatis, compute_apophis)}"""


ENTRY = Entry(
    slug="tumbling-asteroids",
    title="Tumbling asteroids: Toutatis (LAM) and Apophis (SAM), periods, modes and energy",
    order=40,
    compute=compute_asteroids,
    page=_asteroids_page,
)
test_page_is_current = page_test(ENTRY)


def test_toutatis_is_a_lam_and_the_run_reproduces_its_periods():
    t = ENTRY.result()["toutatis"]
    for source, P_phi, P_psi, tol in TOUTATIS_PERIODS:
        found = [x for x in t["rows"] if x["source"] == source]
        assert [x["mode"] for x in found] == ["LAM"]  # one motion at these ratios, the published mode
        x = found[0]
        assert x["measured_mode"] == "LAM"
        assert abs(x["phi"] - P_phi) <= tol and abs(x["psi"] - P_psi) <= tol  # measured: < 1e-9 d
        assert abs(x["phi"] - P_phi) < 1e-6 and abs(x["psi"] - P_psi) < 1e-6


def test_toutatis_periods_admit_only_lam_and_many_shapes():
    t = ENTRY.result()["toutatis"]
    assert t["grid_modes"] == ["LAM"]
    assert t["grid_max"][0] - t["grid_min"][0] > 0.1  # not unique: a wide range of I1/I3


def test_apophis_is_a_sam_with_pravec_energy_under_both_readings():
    e, de = APOPHIS_ENERGY
    for x in ENTRY.result()["apophis"]["rows"]:
        assert "SAM" in x["modes"] and x["measured_mode"] == "SAM", x
        assert abs(x["energy"] - e) <= de, x
        assert abs(x["psi"] - x["P_psi"]) <= APOPHIS_UNCERTAINTY[1], x
        assert abs(x["psi"] - x["P_psi"]) < 1e-6 * x["P_psi"], x  # the run against the closed form


def test_apophis_periods_as_measured_on_the_run():
    for x in ENTRY.result()["apophis"]["rows"]:
        assert abs(x["short_axis3"] - x["short"]) < 1e-6 * x["short"], x  # two measurements of one thing
        published = x["long"] if x["reading"] == "long axis" else x["short"]
        assert abs(published - x["P_phi"]) <= APOPHIS_UNCERTAINTY[0], x
        assert abs(published - x["P_phi"]) < 1e-6 * x["P_phi"], x
        assert abs(1 / x["short"] - 1 / x["long"] - 1 / x["psi"]) < 1e-6 / x["long"], x  # SAM: one turn more


def test_apophis_p1_needs_p_phi_read_as_the_short_axis_precession():
    P1, dP1 = APOPHIS_P1
    rows = {x["reading"]: x for x in ENTRY.result()["apophis"]["rows"] if x["source"] == "Pravec et al. 2014"}
    assert abs(rows["short axis"]["long"] - P1) <= dP1  # the long axis turns with the strongest harmonic
    assert min(abs(rows["long axis"][k] - P1) for k in ("long", "short", "psi")) > 100 * dP1
