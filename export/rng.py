"""The shared PRNG: xoshiro128** seeded by splitmix32, and Box-Muller normals.

Python and TypeScript (web/src/rng/prng.ts) draw the same numbers in the same order:
contract/vectors/prng.json pins seed -> the first uniforms exactly and normals to 1e-12.
Draw order: every normal consumes exactly two uniforms (u1, u2); arrays fill row-major.
"""
from __future__ import annotations

import math

import numpy as np

_M32 = 0xFFFFFFFF


def _rotl(x: int, k: int) -> int:
    return ((x << k) | (x >> (32 - k))) & _M32


def splitmix32(state: int) -> tuple[int, int]:
    """One splitmix32 step: (new state, output)."""
    state = (state + 0x9E3779B9) & _M32
    t = state ^ (state >> 16)
    t = (t * 0x21F0AAAD) & _M32
    t ^= t >> 15
    t = (t * 0x735A2D97) & _M32
    t ^= t >> 15
    return state, t


class Prng:
    def __init__(self, seed: int):
        if not (isinstance(seed, (int, np.integer)) and 0 <= int(seed) <= _M32):
            raise ValueError(f"seed must be an integer in 0..{_M32}, got {seed!r}")
        state = int(seed)
        s = []
        for _ in range(4):
            state, out = splitmix32(state)
            s.append(out)
        if not any(s):  # xoshiro's one forbidden state; splitmix32 never gives it in practice
            s[0] = 1
        self.s = s

    def next_u32(self) -> int:
        s0, s1, s2, s3 = self.s
        result = (_rotl((s1 * 5) & _M32, 7) * 9) & _M32
        t = (s1 << 9) & _M32
        s2 ^= s0
        s3 ^= s1
        s1 ^= s2
        s0 ^= s3
        s2 ^= t
        s3 = _rotl(s3, 11)
        self.s = [s0, s1, s2, s3]
        return result

    def uniform(self) -> float:
        """In [0, 1), exactly u32 / 2^32."""
        return self.next_u32() / 4294967296.0

    def normal(self) -> float:
        u1 = 1.0 - self.uniform()  # (0, 1], so the log is finite
        u2 = self.uniform()
        return math.sqrt(-2.0 * math.log(u1)) * math.cos(2.0 * math.pi * u2)

    def normals(self, shape: tuple[int, ...]) -> np.ndarray:
        n = int(np.prod(shape)) if shape else 1
        return np.asarray([self.normal() for _ in range(n)], dtype=np.float64).reshape(shape)

    def uniforms(self, shape: tuple[int, ...]) -> np.ndarray:
        n = int(np.prod(shape)) if shape else 1
        return np.asarray([self.uniform() for _ in range(n)], dtype=np.float64).reshape(shape)
