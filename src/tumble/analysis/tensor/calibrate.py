"""Calibrating the device: the rotor's inertia, the device's tensor and its centre of mass
(:func:`calibrate_device`)."""

from __future__ import annotations

from collections.abc import Sequence

from .device import Device, Proof, Throw

__all__ = ["calibrate_device"]


def calibrate_device(device: Device, alone: Sequence[Throw], proof_throws: Sequence[Throw], proof: Proof) -> Device:
    """The device with ``rotor_inertia``, ``inertia``, ``center_of_mass`` and their ``_std`` estimated.

    Parameters
    ----------
    device : Device
        Its mass and rotor axis (anything else it holds is replaced).
    alone : sequence of Throw
        Throws of the device alone.
    proof_throws : sequence of Throw
        Throws of the device with the proof body fixed to it.
    proof : Proof
        The proof body's known mass and tensor.

    Returns
    -------
    Device

    Examples
    --------
    >>> from tumble.analysis.tensor import calibrate_device
    >>> callable(calibrate_device)
    True
    """
    raise NotImplementedError
