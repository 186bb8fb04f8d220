"""Draws docs/dual.png: the dual bound s(n) over a circle of directions for two pairs.

Run from the repository root with the package installed: ``python docs/dual_figure.py``.
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import swarmcollide as sc  # noqa: E402


def prism(polygon, z=(-0.5, 0.5)):
    """A prism over a planar polygon, so every direction in the xy-plane sees the polygon."""
    polygon = np.asarray(polygon, dtype=float)
    return np.vstack([np.column_stack([polygon, np.full(len(polygon), h)]) for h in z])


A = prism([[0, 0], [2, 0], [2.2, 1.2], [0.8, 1.8], [-0.3, 0.9]])
B_APART = prism([[2.9, 0.6], [4.2, 0.2], [4.6, 1.5], [3.4, 2.2]])
B_OVERLAP = B_APART - [0.9, 0, 0]

angles = np.linspace(-np.pi, np.pi, 1441)
directions = np.column_stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)])
fig, axes = plt.subplots(1, 2, figsize=(10, 3.6), sharex=True)
for ax, b, title in [(axes[0], B_APART, "apart"), (axes[1], B_OVERLAP, "overlapping")]:
    s = np.array([sc.separation(A, b, n) for n in directions])
    signed = sc.signed_distance(A, b, method="dual")
    ax.plot(np.degrees(angles), s, color="tab:blue", label="s(n): lower bound for every n")
    ax.axhline(signed.distance, color="tab:red", ls="--",
               label="distance" if signed.distance > 0 else "minus penetration depth")
    best = np.degrees(np.arctan2(signed.direction[1], signed.direction[0]))
    ax.plot([best], [signed.distance], "o", color="tab:red", label="dual's answer")
    ax.set_ylim(max(s.min(), -3), 1.5 * max(abs(signed.distance), 0.2))
    ax.set_title(f"{title}: max s = {signed.distance:.6f}")
    ax.set_xlabel("direction angle in the xy-plane (degrees)")
    ax.grid(alpha=0.3)
axes[0].set_ylabel("s(n) = min_j n.y_j - max_i n.x_i")
axes[0].legend(loc="lower center", fontsize=8)
fig.tight_layout()
fig.savefig(Path(__file__).with_name("dual.png"), dpi=110)
