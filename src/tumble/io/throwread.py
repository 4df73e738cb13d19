"""What was read of a throw file or a flight controller's log: :class:`ThrowRead` (shared by
:mod:`tumble.io.throwfile` and :mod:`tumble.io.blackbox`, so that neither imports the other).
"""

from __future__ import annotations

from dataclasses import dataclass

from .gyrocolumns import _UNIT

__all__ = ["ThrowRead"]


@dataclass(frozen=True)
class ThrowRead:
    """Which columns of a throw file were taken, in which units, how many rows.

    Attributes
    ----------
    file : str
        The file as given.
    columns : tuple of str
        The time, wx, wy, wz, rotor, ax, ay, az columns as the header names them
        (``"column 1"`` ... without a header; the last three absent without an accelerometer).
    units : tuple of str
        Their units, converted to s, rad/s and m/s^2.
    ignored : tuple of str
        The columns left out.
    rows : int
        Data rows read.
    axes : tuple of str
        A blackbox log's: the sensor frame's x, y, z as signed axes of the log, which its vectors
        were turned by (``Device.sensor_axes``); empty for a throw file, in the sensor frame.

    Examples
    --------
    >>> from tumble.io.throwread import ThrowRead
    >>> ThrowRead("a1.csv", ("t", "gx", "gy", "gz", "rotor"), ("us", "deg/s", "deg/s", "deg/s", "rpm"), (), 2400).brief()
    't (us), gx, gy, gz (deg/s), rotor (rpm), no accelerometer, 2400 rows'
    """

    file: str
    columns: tuple
    units: tuple
    ignored: tuple
    rows: int
    axes: tuple = ()

    def summary(self) -> dict:
        """JSON-ready (tensor.json's ``"read"``): which column was taken for what, in which unit.

        Examples
        --------
        >>> from tumble.io.throwread import ThrowRead
        >>> read = ThrowRead("a1.csv", ("t", "gx", "gy", "gz", "rotor"), ("us", "deg/s", "deg/s", "deg/s", "rpm"), (), 9)
        >>> read.summary()["rotor"], read.summary()["accel"]
        ({'column': 'rotor', 'unit': 'rpm'}, None)
        """
        def named(k):
            return {"column": self.columns[k], "unit": self.units[k]}

        out = {"file": self.file, "t": named(0), "omega": [named(k) for k in (1, 2, 3)], "rotor": named(4),
               "accel": [named(k) for k in (5, 6, 7)] if len(self.columns) == 8 else None,
               "ignored": list(self.ignored), "rows": int(self.rows)}
        if self.axes:
            out["sensor_axes"] = list(self.axes)
        return out

    def brief(self) -> str:
        """A few words for a command's line.

        Examples
        --------
        >>> from tumble.io.throwfile import THROW_HEADER
        >>> from tumble.io.throwread import ThrowRead
        >>> ThrowRead("p1.csv", THROW_HEADER, ("s", "rad/s", "rad/s", "rad/s", "rad/s", "m/s^2", "m/s^2", "m/s^2"),
        ...           ("temp",), 2400).brief()
        't (s), wx, wy, wz (rad/s), rotor (rad/s), ax, ay, az (m/s^2), 1 ignored, 2400 rows'
        """
        bare = _name_only
        c, u = self.columns, self.units
        parts = [f"{bare(c[0])} ({u[0]})", f"{', '.join(bare(x) for x in c[1:4])} ({'/'.join(dict.fromkeys(u[1:4]))})",
                 f"{bare(c[4])} ({u[4]})"]
        parts.append(f"{', '.join(bare(x) for x in c[5:8])} ({'/'.join(dict.fromkeys(u[5:8]))})" if len(c) == 8
                     else "no accelerometer")
        if self.axes and tuple(self.axes) != ("x", "y", "z"):
            parts.append(f"sensor axes {', '.join(self.axes)}")
        if self.ignored:
            parts.append(f"{len(self.ignored)} ignored")
        return ", ".join([*parts, f"{self.rows} rows"])


def _name_only(cell: str) -> str:
    """A header cell without its unit (a blackbox field's index, ``gyroADC[0]``, is no unit)."""
    match = _UNIT.search(cell)
    return cell[:match.start()].strip() if match and not match.group(1).isdigit() else cell


