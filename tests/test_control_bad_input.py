"""Bad values in a control scenario: one ValueError naming the key (the CLI's one line and exit 2)."""

from __future__ import annotations

import copy

import pytest

from tumble.cli import main
from tumble.io.bodyfile import body_from_table
from tumble.io.controlfile import control_scenario_from_table

BODY = {"name": "box", "parts": [{"kind": "box", "mass": 4.0, "size": [0.1, 0.2, 0.3]}]}
POINT = {"initial": {"omega": [0.0, 0.0, 0.01]}, "simulation": {"t_end": 1.0},
         "control": {"kind": "mrp_pd", "period": 0.5, "K": 1e-3, "P": 6e-3},
         "actuators": {"wheels": {"inertia": 2e-5, "max_torque": 2e-3}}}
DETUMBLE = {"initial": {"omega": [0.1, 0.1, 0.1]}, "simulation": {"t_end": 1.0},
            "orbit": {"altitude": 500e3, "inclination": 1.7}, "actuators": {"magnetorquers": {"max_dipole": 0.2}},
            "control": {"kind": "bdot", "period": 1.0}}


def _build(base: dict, section: str, **changes: object):
    table = copy.deepcopy(base)
    table[section].update(changes)
    return control_scenario_from_table(table, body_from_table(BODY))


@pytest.mark.parametrize("kind", [[1], {"a": 1}, 3])
def test_a_kind_that_is_not_a_string_is_refused_by_name(kind):
    with pytest.raises(ValueError, match=r"^control: kind = .* is unknown; allowed: bdot, mrp_pd, detumble_point$"):
        _build(POINT, "control", kind=kind)


@pytest.mark.parametrize(("section", "base", "key"), [("orbit", DETUMBLE, "gravity_gradient"),
                                                      ("orbit", DETUMBLE, "earth_rotation"),
                                                      ("control", POINT, "gyroscopic")])
def test_a_switch_given_as_a_string_is_refused_not_read_as_true(section, base, key):
    with pytest.raises(ValueError, match=rf"^{section}: {key} = 'no' must be true or false$"):
        _build(base, section, **{key: "no"})
    on = _build(base, section, **{key: True})
    off = _build(base, section, **{key: False})
    value = {"gravity_gradient": lambda s: s.gravity_gradient, "earth_rotation": lambda s: s.field.earth_rotation,
             "gyroscopic": lambda s: s.controller().gyroscopic}[key]
    assert (value(on), value(off)) == (True, False)


def test_the_cli_gives_one_line_and_exit_2_and_writes_nothing(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text('body = { name = "b", parts = [{ kind = "box", mass = 4.0, size = [0.1, 0.2, 0.3] }] }\n'
                    "initial = { omega = [0.0, 0.0, 0.01] }\nsimulation = { t_end = 1.0 }\n"
                    "[actuators.wheels]\ninertia = 2e-5\n[control]\nkind = [1]\nperiod = 0.5\n")
    out = tmp_path / "out"
    assert main(["simulate", str(path), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "control: kind = [1] is unknown" in err
    assert not out.exists()
