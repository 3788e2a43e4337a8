import re

import numpy as np

from export.data import deepmimic
from export.data.skeleton import SKELETON, URDF_SCALE


def urdf_joint_origins():
    text = (deepmimic.pybullet_data_dir() / "humanoid" / "humanoid.urdf").read_bytes()
    text = text.rstrip(b"\0").decode()  # the file ends in a NUL byte strict parsers reject
    out = {}
    for m in re.finditer(r'<joint name="(\w+)".*?<origin rpy = "[^"]*" xyz = "([^"]+)"', text, re.S):
        out[m.group(1)] = np.array([float(v) for v in m.group(2).split()]) * URDF_SCALE
    return out


def test_offsets_are_the_urdf_joint_origins_times_a_quarter():
    origins = urdf_joint_origins()
    for name in ["chest", "neck", "right_hip", "right_knee", "right_ankle", "right_shoulder", "right_elbow",
                 "right_wrist", "left_hip", "left_knee", "left_ankle", "left_shoulder", "left_elbow", "left_wrist"]:
        np.testing.assert_allclose(SKELETON.offsets[SKELETON.index(name)], origins[name], atol=1e-12, err_msg=name)


def test_skeleton_is_symmetric_and_ordered():
    assert SKELETON.num_joints == 18
    for j, p in enumerate(SKELETON.parents):
        assert p < j
    m = SKELETON.mirror_map
    mirrored = SKELETON.offsets[m] * np.array([1, 1, -1])
    np.testing.assert_allclose(mirrored, SKELETON.offsets, atol=1e-12)
