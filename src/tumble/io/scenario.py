"""Scenario files (TOML): a body, an initial spin and how to integrate it.

::

    body = "t-handle"          # a preset name, a body file (relative to this file), or a [body] table

    [initial]
    omega = [0.1, 10.0, 0.1]   # rad/s
    frame = "principal"        # "principal" (axes ordered I1 <= I2 <= I3) or "design"

    [simulation]
    t_end = 20.0               # s
    samples = 500
    method = "exact"           # "exact", "dop853", "rk45", "seed", "geometric", "geometric2", "geometric6"
    # rtol = 1e-12             # optional tolerances (dop853, rk45, seed)
    # atol = 1e-12
    # step = 1e-3              # optional largest step of the geometric methods, s

    [torque]                   # optional: a constant torque
    vector = [0.0, 0.0, 0.01]  # N m
    frame = "body"             # "body" or "world"

Keys are checked strictly; every error is one line naming the file and the key.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..dynamics import ConstantTorque, Trajectory, simulate
from ..dynamics.simulate import check_inputs
from ..mass import PRESETS, Body
from .bodyfile import body_from_table, load_body, read_toml

__all__ = ["Scenario", "load_scenario", "scenario_from_table"]

_SECTIONS = {
    "initial": {"omega", "frame"},
    "simulation": {"t_end", "samples", "method", "rtol", "atol", "step"},
    "torque": {"vector", "frame"},
}


@dataclass(frozen=True, eq=False)
class Scenario:
    """A parsed scenario: everything :func:`tumble.simulate` needs."""

    body: Body
    omega: tuple[float, float, float]
    frame: str = "principal"
    t_end: float = 20.0
    samples: int = 500
    method: str | None = None
    rtol: float | None = None
    atol: float | None = None
    step: float | None = None
    torque: ConstantTorque | None = None
    name: str = "scenario"

    def run(self) -> Trajectory:
        """Simulate the scenario."""
        return simulate(
            self.body, self.omega, t_end=self.t_end, samples=self.samples, method=self.method,
            frame=self.frame, torque=self.torque, rtol=self.rtol, atol=self.atol, step=self.step,
        )


def scenario_from_table(data: dict, *, base_dir: Path | None = None, name: str = "scenario") -> Scenario:
    """Build a scenario from parsed TOML; values are validated by the constructors they feed."""
    unknown = sorted(set(data) - {"body", *_SECTIONS})
    if unknown:
        raise ValueError(f"unknown key {unknown[0]!r}; allowed: body, {', '.join(_SECTIONS)}")
    if "body" not in data:
        raise ValueError("missing key 'body' (a preset name, a body file or a [body] table)")
    body = _body(data["body"], base_dir)
    tables = {}
    for section, keys in _SECTIONS.items():
        table = data.get(section, {})
        if not isinstance(table, dict):
            raise ValueError(f"{section} must be a table [{section}]")
        bad = sorted(set(table) - keys)
        if bad:
            raise ValueError(f"{section}: unknown key {bad[0]!r}; allowed: {', '.join(sorted(keys))}")
        tables[section] = table
    initial, sim, torque = tables["initial"], tables["simulation"], tables["torque"]
    if "omega" not in initial:
        raise ValueError("initial: missing key 'omega' (rad/s)")
    frame = initial.get("frame", "principal")
    method = sim.get("method")
    model = None
    if torque:
        if "vector" not in torque:
            raise ValueError("torque: missing key 'vector' (N m)")
        try:
            model = ConstantTorque(torque["vector"], torque.get("frame", "body"))
        except ValueError as exc:
            raise ValueError(f"torque: {exc}") from None
    scenario = Scenario(
        body=body, omega=initial["omega"], frame=frame, t_end=sim.get("t_end", 20.0),
        samples=sim.get("samples", 500), method=method, rtol=sim.get("rtol"), atol=sim.get("atol"),
        step=sim.get("step"), torque=model, name=name,
    )
    _validate(scenario)
    return scenario


def _body(spec, base_dir: Path | None) -> Body:
    if isinstance(spec, dict):
        return body_from_table(spec, base_dir=base_dir)
    if not isinstance(spec, str):
        raise ValueError(f"body = {spec!r} must be a preset name, a body file path or a [body] table")
    if spec in PRESETS:
        return PRESETS[spec]()
    path = Path(spec) if base_dir is None else base_dir / spec
    if not path.exists():
        raise ValueError(f"body = {spec!r} is neither a preset ({', '.join(PRESETS)}) nor a file")
    return load_body(path)


def _validate(s: Scenario) -> None:
    """Check the numbers now, so that nothing is computed or written for a bad file.

    :func:`simulate`'s own checks keep one source of truth for the messages; the argument
    names are replaced by the file's keys.
    """
    keys = {"omega0": "initial.omega", "t_end": "simulation.t_end", "samples": "simulation.samples",
            "rtol": "simulation.rtol", "atol": "simulation.atol", "step": "simulation.step",
            "method": "simulation.method", "frame": "initial.frame"}
    try:
        check_inputs(s.body, s.omega, t_end=s.t_end, samples=s.samples, method=s.method,
                     frame=s.frame, rtol=s.rtol, atol=s.atol, step=s.step, torque=s.torque)
    except ValueError as exc:
        message = str(exc)
        for old, new in keys.items():
            if message.startswith(old):
                message = new + message[len(old):]
                break
        raise ValueError(message) from None


def load_scenario(path) -> Scenario:
    """Read and validate a scenario file; errors are one line starting with the file's name."""
    path = Path(path)
    data = read_toml(path)
    try:
        return scenario_from_table(data, base_dir=path.parent, name=path.stem)
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None
