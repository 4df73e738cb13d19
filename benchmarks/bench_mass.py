"""Mass-properties benchmarks: a 10-part body and a 100k-triangle mesh part.

Each case is timed against a baseline in the same run; the ratio is what to compare across
machines, the absolute time is what the targets of the foundation issue name
(10-part body well under 1 ms; 100k-triangle mesh part under 0.2 s).
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

import tumble


def ten_parts():
    rng = np.random.default_rng(0)
    parts = []
    for k in range(10):
        c = tuple(rng.normal(size=3))
        kind = k % 5
        if kind == 0:
            parts.append(tumble.Rod(mass=1.0, length=1.0, center=c, axis=tuple(rng.normal(size=3))))
        elif kind == 1:
            parts.append(tumble.Cylinder(density=1000.0, radius=0.1, length=0.5, center=c, axis=tuple(rng.normal(size=3))))
        elif kind == 2:
            parts.append(tumble.Box(mass=2.0, size=(0.1, 0.2, 0.3), center=c, rotation=Rotation.random(random_state=k)))
        elif kind == 3:
            parts.append(tumble.Sphere(mass=0.5, radius=0.2, center=c))
        else:
            parts.append(tumble.PointMass(mass=0.1, center=c))
    return tuple(parts)


def cases():
    """(name, candidate, baseline, baseline description, target seconds or None)."""
    import trimesh

    parts = ten_parts()
    m = np.array([p.mass for p in parts])
    r = np.array([p.center for p in parts])
    own = np.array([p.inertia for p in parts])

    def bare_numpy():
        # the irreducible arithmetic: COM, parallel-axis sum, one eigh; no checks, no objects
        com = (m[:, None] * r).sum(0) / m.sum()
        d = r - com
        I = own.sum(0) + np.einsum("k,kij->ij", m, np.einsum("ki,ki->k", d, d)[:, None, None] * np.eye(3) - d[:, :, None] * d[:, None, :])
        return np.linalg.eigh(I)

    mesh = trimesh.creation.torus(major_radius=1.0, minor_radius=0.3, major_sections=250, minor_sections=200)
    n_faces = len(mesh.faces)

    def trimesh_alone():
        fresh = mesh.copy()
        return fresh.mass_properties

    return [
        ("Body of 10 parts (mass properties, checks, principal frame)", lambda: tumble.Body(parts), bare_numpy,
         "bare numpy sum + eigh", 1e-3),
        (f"Mesh part of {n_faces} triangles (load checks + properties)", lambda: tumble.Mesh(mesh=mesh, mass=1.0),
         trimesh_alone, "trimesh mass_properties alone", 0.2),
    ]
