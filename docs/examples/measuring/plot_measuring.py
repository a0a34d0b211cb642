"""
Measuring the slope, anisotropy and motion of any image or video
================================================================

The analysers of :mod:`noiselab.analysis` work on any array: an image made
elsewhere, a frame of a film, a video. Here they measure a 1/f^1.5 image, a
striped image and a falling-snow video. For a file use
``noiselab.io.read_image`` / ``read_video``, or the command line:
``noiselab analyze FILE --plot out.png``.
"""
import matplotlib.pyplot as plt
import numpy as np

import noiselab
from noiselab import analysis

rough = noiselab.spectral_noise((256, 256), exponent=1.5, rng=0)
y, x = np.mgrid[:256, :256]
stripes = np.sin(2 * np.pi * (x + 0.3 * y) / 16) + 0.3 * rough
for name, image in (("1/f^1.5", rough), ("stripes", stripes)):
    print(f"{name}: amplitude slope {float(analysis.spectral_slope(image)):.2f}, "
          f"anisotropy {analysis.anisotropy(image):.3f}")

video = noiselab.snow((32, 128, 128), rng=2, direction_yx=(1, 1))
profile = analysis.speed_profile(video)
print("snow: best velocity", np.round(analysis.best_velocity(video), 2), "px/frame")

fig, axes = plt.subplots(1, 3, figsize=(10, 3))
axes[0].imshow(rough, cmap="gray")
axes[0].set_title("1/f^1.5")
axes[1].imshow(stripes, cmap="gray")
axes[1].set_title("stripes + noise")
for ax in axes[:2]:
    ax.axis("off")
axes[2].loglog(profile.centers, np.hypot(*np.asarray(profile.velocity).T), "o-")
axes[2].set_xlabel("band centre (cycles/frame)")
axes[2].set_ylabel("speed (px/frame)")
axes[2].set_title("snow: speed per band")
fig.tight_layout()
