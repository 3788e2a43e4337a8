"""The orthonormal DCT-II basis, the one WAT's smoothness prior (Eq. 4) and the baselines use."""
from __future__ import annotations

import numpy as np
from scipy.fft import dct


def dct_basis(frames: int, bases: int) -> np.ndarray:
    """D [frames, bases]: the first `bases` orthonormal DCT-II basis vectors as columns.

    For a sequence Z [frames, K], coefficients are D.T @ Z and D @ D.T @ Z keeps its `bases`
    lowest frequencies.
    """
    if not 0 < bases <= frames:
        raise ValueError(f"need 0 < bases <= frames, got {bases} bases for {frames} frames")
    full = dct(np.eye(frames), norm="ortho", axis=0)  # rows are basis vectors
    return full[:bases].T.copy()
