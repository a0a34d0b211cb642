"""
1/f noise of a given exponent and band
======================================

:func:`noiselab.spectral_noise` draws isotropic noise with amplitude
``1/f**exponent`` (power ``1/f**(2 exponent)``) inside ``band`` (cycles/frame).
:func:`noiselab.analysis.spectral_slope` fits the amplitude slope back (``-exponent``).
"""
import matplotlib.pyplot as plt

import noiselab
from noiselab import analysis

fig, axes = plt.subplots(1, 4, figsize=(11, 2.8))
for ax, exponent in zip(axes[:3], (0.5, 1.0, 1.5)):
    field = noiselab.spectral_noise((256, 256), exponent=exponent, band=(4, 64), rng=0)
    slope = analysis.spectral_slope(field, band=(4, 64))
    print(f"exponent {exponent}: fitted amplitude slope {float(slope):.2f} (law {-exponent})")
    ax.imshow(field, cmap="gray")
    ax.set_title(f"1/f^{exponent}, band 4-64")
    ax.axis("off")
    spectrum = analysis.radial_spectrum(field)
    axes[3].loglog(spectrum.centers[1:], spectrum.power[1:], label=f"exponent {exponent}")
axes[3].set_xlabel("cycles/frame")
axes[3].set_ylabel("power")
axes[3].legend(fontsize=7)
fig.tight_layout()
