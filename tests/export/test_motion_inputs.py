"""What the networks read (export/models/inputs.py), slowed training motion (export/ops/time_scale.py) and
the per-second speed term for prior samples (export/ops/speed_term.py), on small hand-made motions."""
import numpy as np
import pytest
import torch

from export.data.skeleton import SKELETON
from export.models import inputs
from export.ops.facing import ROOT_CHANNEL
from export.ops.speed_term import per_second_speed_term
from export.ops.time_scale import slow_down, slowed_length

J = SKELETON.num_joints
K = J * 3


def walk(frames: int, start: int = 0, speed: float = 0.05) -> torch.Tensor:
    """[1, frames, J, 3]: the root travelling +z by `speed` a frame from frame `start` (root channel 0 there),
    the other joints swinging in x."""
    t = torch.arange(start, start + frames, dtype=torch.float64)
    m = torch.zeros(1, frames, J, 3, dtype=torch.float64)
    m[0, :, 0, 2] = t * speed
    m[0, :, 1:, 0] = 0.1 * torch.sin(t / 3)[:, None]
    m[0, :, 1:, 1] = 1.0
    return m


def test_history_steps_sit_beside_the_poses_and_the_first_frame_has_none():
    history = walk(10, start=-9)
    mean, std, step_std = torch.zeros(K), torch.full((K,), 2.0), torch.full((K,), 0.01)
    plain = inputs.history_features(history, mean, std, step_std, steps=False)
    both = inputs.history_features(history, mean, std, step_std, steps=True)
    assert plain.shape == (1, 10, K) and both.shape == (1, 10, 2 * K)
    assert torch.equal(both[..., :K], plain)
    flat = history.flatten(2)
    assert torch.equal(both[0, 0, K:], torch.zeros(K, dtype=both.dtype))        # no frame before the first
    assert torch.allclose(both[0, 1:, K:], (flat[0, 1:] - flat[0, :-1]) / 0.01)


def test_the_future_input_reads_root_steps_not_how_far_the_root_has_gone():
    mean, std, step_std = torch.zeros(K), torch.ones(K), torch.full((K,), 0.05)
    near, far = walk(30, start=1), walk(30, start=1) + 0.0
    far[..., 0, 2] += 40.0                        # the same gait 40 m further on
    a = inputs.future_features(near, mean, std, step_std, "step")
    b = inputs.future_features(far, mean, std, step_std, "step")
    root = list(ROOT_CHANNEL)
    # the first step is measured from the present, where the root channel is 0 (canonical frame)
    assert torch.allclose(a[0, :, root[1]][1:], torch.ones(29, dtype=a.dtype))
    assert a[0, 0, root[1]].item() == pytest.approx(0.05 / 0.05)
    assert torch.allclose(a[..., 3:], b[..., 3:]) and torch.allclose(a[0, 1:, root], b[0, 1:, root])
    # "position" keeps the input as it was: the root's place, which grows with the walk
    pos = inputs.future_features(far, mean, std, step_std, "position")
    assert pos[0, -1, root[1]].item() == pytest.approx(far[0, -1, 0, 2].item())


def test_the_decoder_mask_hides_only_the_root_channel_position():
    assert torch.equal(inputs.pose_input_mask(K, "position"), torch.ones(K))
    mask = inputs.pose_input_mask(K, "step")
    assert mask.sum().item() == K - 2 and all(mask[i] == 0 for i in ROOT_CHANNEL)
    with pytest.raises(ValueError, match="root_input"):
        inputs.check_root_input("velocity")


def test_slowing_keeps_the_present_and_replays_the_motion_in_between():
    seq = walk(40, start=-9)
    history, future = seq[:, :10], seq[:, 10:]
    same_h, same_f = slow_down(history, future, torch.tensor([1.0]))
    assert torch.allclose(same_h, history) and torch.allclose(same_f, future)
    h, f = slow_down(history, future, torch.tensor([0.5]))
    assert torch.allclose(h[:, -1], history[:, -1])                              # the present stays
    # future frame 2i + 1 (time i + 1 at half speed) is original future frame i; odd times interpolate
    assert torch.allclose(f[:, 1::2][:, :15], future[:, :15])
    assert torch.allclose(f[:, 0], (history[:, -1] + future[:, 0]) / 2)
    assert torch.allclose(h[:, -3], history[:, -2])
    # the root travels at half the speed
    assert (f[0, 1:, 0, 2] - f[0, :-1, 0, 2]).mean().item() == pytest.approx(0.025)
    assert slowed_length(torch.tensor([30, 7]), torch.tensor([0.5, 0.1])).tolist() == [60, 70]
    with pytest.raises(ValueError, match="factors"):
        slow_down(history, future, torch.tensor([0.0]))


def test_the_per_second_speed_term_asks_how_fast_not_when():
    hist = walk(10, start=-9)
    truth = walk(60, start=1)
    mask = torch.ones(1, 60, dtype=torch.bool)
    assert per_second_speed_term(hist, truth, truth, mask).item() == pytest.approx(0.0, abs=1e-20)
    still = hist[:, -1:].repeat(1, 60, 1, 1)
    frozen = per_second_speed_term(hist, still, truth, mask).item()
    assert frozen > 0.01
    # the same swing at another phase costs much less than standing still
    shifted = walk(60, start=17)
    shifted[..., 0, 2] = truth[..., 0, 2]
    assert per_second_speed_term(hist, shifted, truth, mask).item() < 0.1 * frozen
    # seconds with less than half their frames supervised do not count
    half = torch.zeros(1, 60, dtype=torch.bool)
    half[:, :10] = True
    assert per_second_speed_term(hist, still, truth, half).item() == pytest.approx(0.0)
