"""The lab's own comparisons: spectral against lattice noise, measured with the same instruments."""
from __future__ import annotations

import numpy as np

from ..registry import Result, figure
