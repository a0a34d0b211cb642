"""
Spectral and lattice noise on one scene
=======================================

The same 1/f texture two ways: :func:`noiselab.spectral_noise` shapes the
spectrum exactly and inverts it; :func:`noiselab.fractal_sum` adds octaves of
lattice noise (gain 1/2, lacunarity 2: amplitude ~ 1/f). The radial spectra and
the anisotropy index show where they differ (the laboratory, ``noiselab bench``,
does this at scale: see the benchmarks pages).
"""
import matplotlib.pyplot as plt

import noiselab
from noiselab import analysis
from noiselab.lattice import Grid

size = 256
spectral = noiselab.spectral_noise((size, size), exponent=1.0, band=(2, 64), rng=0)
lattice = noiselab.fractal_sum(noiselab.LatticeNoise(2, rng=0, kernel="quintic", basis="gradient"),
                               Grid((size, size), ((0, 4), (0, 4))), 5)

fig, axes = plt.subplots(1, 3, figsize=(10, 3))
for ax, (name, field) in zip(axes, (("spectral", spectral), ("lattice fractal sum", lattice))):
    slope = float(analysis.spectral_slope(field, band=(4, 64)))
    aniso = analysis.anisotropy(field, band=(4, 64))
    print(f"{name}: amplitude slope {slope:.2f}, anisotropy {aniso:.3f}")
    ax.imshow(field, cmap="gray")
    ax.set_title(f"{name}\nslope {slope:.2f}, anisotropy {aniso:.2f}", fontsize=9)
    ax.axis("off")
    spectrum = analysis.radial_spectrum(field)
    axes[2].loglog(spectrum.centers[1:], spectrum.power[1:] / spectrum.power[1:].max(), label=name)
axes[2].set_xlabel("cycles/frame")
axes[2].set_ylabel("power (normalised)")
axes[2].legend(fontsize=7)
fig.tight_layout()
