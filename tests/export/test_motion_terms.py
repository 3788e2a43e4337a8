"""The speed and skate terms (export/ops/speed_term.py, skate_term.py), by hand."""
import numpy as np
import pytest
import torch

from export.data.skeleton import SKELETON
from export.ops.skate_term import BAND, SOFTNESS, floor_places, skate_term
from export.ops.speed_term import displacement_speeds, speed_term

J = SKELETON.num_joints


def motion(frames: int, step: float, height: float = 0.5, joint: int | None = None) -> torch.Tensor:
    """[1, frames, J, 3]: every joint (or one) moving `step` metres per frame along x, root-relative."""
    m = torch.zeros(1, frames, J, 3, dtype=torch.float64)
    m[..., 1] = height
    joints = slice(1, None) if joint is None else slice(joint, joint + 1)
    m[0, :, joints, 0] = torch.arange(frames, dtype=torch.float64)[:, None] * step
    return m


def test_displacement_speeds_are_root_relative_and_over_the_lag():
    hist, fut = motion(12, 0.01)[:, :5], motion(12, 0.01)[:, 5:]
    got = displacement_speeds(hist, fut, lag=5, fps=30.0)
    # every non-root joint moves 0.01 m a frame: 0.3 m/s, whatever the lag; the root joint stands
    assert torch.allclose(got[..., 1:], torch.full_like(got[..., 1:], 0.3))
    assert torch.allclose(got[..., 0], torch.zeros_like(got[..., 0]))
    # travel of the root channel alone is not speed here (the reconstruction has it)
    travel = fut.clone()
    travel[..., 0, 0] += torch.arange(7, dtype=torch.float64)[None, :] * 0.5
    assert torch.allclose(displacement_speeds(hist, travel, 5), got)


def test_a_still_prediction_pays_for_the_speed_it_misses_and_a_phase_shift_does_not():
    hist = motion(20, 0.01)[:, :10]
    truth = motion(20, 0.01)[:, 10:]
    still = truth[:, :1].repeat(1, 10, 1, 1)
    # (0.3 - 0)^2 on the 17 moving joints, 0 on the root, averaged over 18 joints, on the frames past the lag
    lagged = torch.zeros(1, 10, dtype=torch.bool)
    lagged[:, 5:] = True
    assert speed_term(hist, still, truth, lagged).item() == pytest.approx(0.09 * 17 / 18)
    # an oscillation at the truth's speed but another phase: the same speeds, no cost
    t = torch.arange(30, dtype=torch.float64)
    a = torch.zeros(1, 30, J, 3, dtype=torch.float64)
    b = a.clone()
    a[0, :, 1:, 0] = (0.1 * torch.sin(2 * np.pi * t / 10))[:, None]
    b[0, :, 1:, 0] = (0.1 * torch.sin(2 * np.pi * (t + 5) / 10))[:, None]     # half a period later
    assert speed_term(a[:, :10], a[:, 10:], b[:, 10:]).item() > 0              # the history's frames differ...
    assert speed_term(a[:, :10], a[:, 10:], a[:, 10:]).item() == pytest.approx(0.0)
    mid = torch.zeros(1, 20, dtype=torch.bool)
    mid[:, 5:] = True                                                          # ...but past the lag it is free
    assert speed_term(a[:, :10], a[:, 10:], b[:, 10:], mid).item() == pytest.approx(0.0, abs=1e-20)


def test_the_skate_term_charges_a_foot_that_slides_on_the_floor_not_one_that_swings():
    foot = SKELETON.index("left_toe")
    hist = motion(1, 0.0, height=0.0)
    sliding = motion(4, 0.02, height=0.0, joint=foot)                          # on the floor, 0.6 m/s
    swinging = motion(4, 0.02, height=0.0, joint=foot)
    swinging[..., foot, 1] = 0.3                                                # 30 cm up
    w = 1 / (1 + np.exp(-BAND / SOFTNESS))                                      # sigmoid((0.03 - 0) / 0.01)
    # one of four feet slides at 0.6 m/s on the three frames after the first (the first step is 0)
    expected = w * 0.36 * 3 / (4 * 4) + 3 * w * 0 / 16
    assert skate_term(hist, sliding).item() == pytest.approx(expected, rel=1e-6)
    assert skate_term(hist, swinging).item() < 1e-8
    # the place on the floor follows the root channel: a planted foot under a travelling root slides
    planted = motion(4, 0.0, height=0.0)
    planted[..., 0, 0] = torch.arange(4, dtype=torch.float64) * 0.02
    assert torch.allclose(floor_places(planted)[0, :, 0, 0], planted[0, :, 0, 0])
    assert skate_term(hist, planted).item() == pytest.approx(w * 0.36 * 3 / 4, rel=1e-6)
