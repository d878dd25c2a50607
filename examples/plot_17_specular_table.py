"""
The specular look-up table
==========================

Fast Phong shading pays no power per pixel: the specular term Isr cos^n φ,
quantised to whole intensity levels, is j exactly when cos φ lies between the
breakpoints cos φ_j = (j / N)^(1/n) and cos φ_(j+1), so a table of N
breakpoints and a few comparisons give the level (Wang 1989, ch. 3,
"Specular Reflection", Tables 3-1 to 3-4). Here is Table 3-4 (Ip = 255,
ks = 0.7, r + r0 = 1.5, n = 8): its entries on the exact curve, and the level
the table gives against the exact, unquantised value.
"""

import matplotlib.pyplot as plt
import numpy as np

from scanviz.shading import lut_levels, specular_levels_exact, specular_lut, table_size

Ip, ks, r_plus_r0, n = 255, 0.7, 1.5, 8
table = specular_lut(Ip, ks, r_plus_r0, n)
N = table_size(Ip, ks, r_plus_r0)
cosines = np.linspace(0.4, 1.0, 20001)
exact = N * cosines**n
levels = lut_levels(table, cosines)
disagree = int((levels != specular_levels_exact(N, n, cosines)).sum())

# %%
# Left: each table entry is where the exact curve N cos^n φ reaches a whole
# level j. Right: the table's level minus the exact value lies in (-1, 0]:
# the table truncates, as floor does.

fig, (curve_ax, error_ax) = plt.subplots(1, 2, figsize=(10, 4))
curve_ax.plot(cosines, exact, color="black", lw=1, label=f"exact {N} cos$^{n}$ φ")
curve_ax.plot(table, np.arange(1, N + 1), "o", ms=3, color="tab:orange", label="table entries")
curve_ax.step(cosines, levels, where="post", lw=0.8, color="tab:blue", label="level looked up")
curve_ax.set_xlabel("cos φ")
curve_ax.set_ylabel("specular intensity level")
curve_ax.set_xlim(0.55, 0.8)  # the first levels, where the steps are wide enough to see
curve_ax.set_ylim(0, 20)
curve_ax.set_title(f"Table 3-4: the first of its N = {N} entries", fontsize=10)
curve_ax.legend(fontsize=8)

error_ax.plot(exact, levels - exact, lw=0.5, color="tab:blue")
error_ax.set_xlabel(f"exact value {N} cos$^{n}$ φ")
error_ax.set_ylabel("table level − exact N cos$^n$ φ")
error_ax.set_title(
    f"level error: from {(levels - exact).min():.4f} to {(levels - exact).max():.4f}\n"
    f"floor(N cos$^n$ φ) differs at {disagree} of {len(cosines):,} cosines",
    fontsize=10,
)
fig.tight_layout()
plt.show()
