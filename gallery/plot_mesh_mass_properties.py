"""
Mass properties of a mesh
=========================

A part from a closed triangle mesh (STL, OBJ or PLY, read with trimesh: the extra
``tumble[mesh]``): its volume, centre of mass and inertia tensor from the mesh's signed
tetrahedra. The torus that ships with tumble (major radius R = 0.04 m, minor r = 0.01 m, 1536 facets)
against the solid torus's closed form: ``I_axis = m (R^2 + 3 r^2 / 4)``,
``I_diameter = m (R^2 / 2 + 5 r^2 / 8)``.
"""

from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

import tumble

path = files("tumble") / "examples" / "bodies" / "meshes" / "torus.stl"
torus = tumble.Body([tumble.Mesh(mesh=str(path), density=1000.0)])  # kg/m^3
m = torus.mass
R, r = 0.04, 0.01  # m
closed = np.array([m * (R**2 / 2 + 5 * r**2 / 8), m * (R**2 / 2 + 5 * r**2 / 8), m * (R**2 + 3 * r**2 / 4)])
print(f"mass {m:.4f} kg (solid torus {1000 * 2 * np.pi**2 * R * r**2:.4f} kg), centre of mass {np.round(torus.com, 12)} m")
print(f"principal moments {torus.principal_moments} kg m^2, closed form with this mass {closed}")

# %%
# The mesh's principal moments beside the closed form's.

fig, ax = plt.subplots(layout="constrained")  # room for the labels
ax.bar(np.arange(3) - 0.2, torus.principal_moments, width=0.4, label="mesh")
ax.bar(np.arange(3) + 0.2, closed, width=0.4, label="solid torus, closed form (same mass)")
ax.legend()
ax.set(xticks=range(3), xticklabels=["I1", "I2", "I3"], ylabel="principal moment (kg m^2)")
plt.show()
