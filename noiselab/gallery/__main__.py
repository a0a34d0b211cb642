"""``python3 -m noiselab.gallery``: build the gallery (the same as ``noiselab gallery``)."""
import sys

from .build import main

sys.exit(main())
