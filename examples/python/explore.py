# %% [markdown]
# # stickslip from Python
#
# A notebook-style script (cells marked `# %%`; it runs as a plain script
# too): a parameter loop with dotted overrides, a sweep into a pandas
# DataFrame, and a matplotlib figure of both.
#
#     python examples/python/explore.py [OUTPUT_DIR]

# %%
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import stickslip

out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(".")
out.mkdir(parents=True, exist_ok=True)

# %% [markdown]
# ## One run
# The paper's motor and signal (n = 2, sqrt(kappa) = 6, sigma factors).

# %%
scene = stickslip.default_scene()
r = stickslip.run(scene)
print(f"v_inf = {r.v_inf:.6g} m/s (error {r.error['v_inf']:.1e}), regime {r.regime}")

# %% [markdown]
# ## A parameter loop: the slider mass
# Each run overrides one field by its dotted path, as `--set` does.

# %%
masses = np.geomspace(0.5e-3, 8e-3, 9)
v_inf = [stickslip.run(scene, **{"motor.slider_mass": m}).v_inf for m in masses]
for m, v in zip(masses, v_inf):
    print(f"m = {m * 1e3:5.2f} g: v_inf = {v * 1e3:7.2f} mm/s")

# %% [markdown]
# ## A sweep: section 7 of the paper
# Signals of equal highest frequency f_max = n f_0 (level L = n sqrt(kappa))
# across the number of harmonics n, with the sigma factors.

# %%
grid = stickslip.sweep(
    scene,
    {"level": [3, 6, 9, 12, 15], "harmonics": [2, 3, 4, 6, 8], "sigma": [True]},
    indicators=["v_inf", "smoothness"],
    timing=False,
)
print(grid[["level", "harmonics", "regime", "v_inf", "smoothness"]].head(10).to_string())

# %% [markdown]
# ## The figure

# %%
fig, (left, right) = plt.subplots(1, 2, figsize=(7.0, 2.8), constrained_layout=True)
left.plot(np.asarray(masses) * 1e3, np.asarray(v_inf) * 1e3, "o-", color="0.2")
left.set_xscale("log")
left.set_xticks([0.5, 1, 2, 4, 8], ["0.5", "1", "2", "4", "8"])
left.minorticks_off()
left.set_xlabel("slider mass $m$ (g)")
left.set_ylabel(r"$v_\infty$ (mm/s)")
for n, rows in grid.groupby("harmonics"):
    right.plot(rows["level"], rows["v_inf"] * 1e3, "o-", label=f"$n$ = {n}")
right.set_xticks(sorted(grid["level"].unique()))
right.set_ylim(bottom=0)
right.set_xlabel(r"level $L = n\sqrt{\kappa}$")
right.set_ylabel(r"$v_\infty$ (mm/s)")
right.legend(frameon=False, fontsize=8)
figure = out / "explore.png"
fig.savefig(figure, dpi=200)
print(f"wrote {figure}")
