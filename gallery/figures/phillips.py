"""Phillips, "Creating noisy stimuli" (Perception 2004): figures 1-5 and 7-20."""
from __future__ import annotations

import numpy as np

from ..registry import Result, figure
