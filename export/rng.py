"""The shared PRNG: xoshiro128** seeded by splitmix32, and Box-Muller normals.

Python and TypeScript (web/src/rng/prng.ts) draw the same numbers in the same order:
contract/vectors/prng.json pins seed -> the first uniforms exactly and normals to 1e-12.
Draw order: every normal consumes exactly two uniforms (u1, u2); arrays fill row-major.

Samples that nest (issue 30 item 6): a predictor gives sample i its own stream, streams(seed, K)[i] =
Prng(seed) advanced by i x 2^64 draws (xoshiro128**'s jump), so sample i's numbers depend on (seed, i)
only and the first k samples of a prediction with K > k are the k samples of one with K = k. Stream 0
is Prng(seed) itself. Not in the model-hash closure (export.pipeline does not import it).
"""
from __future__ import annotations

import math

import numpy as np

_M32 = 0xFFFFFFFF
# xoshiro128**'s jump polynomial: jump() moves the state 2^64 draws ahead (tests/export/test_nesting.py
# checks it against the state transition raised to the 2^64th power over GF(2)).
JUMP = (0x8764000B, 0xF542D2D3, 0x6FA035C3, 0x77F2DB5B)


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

    def copy(self) -> "Prng":
        out = Prng.__new__(Prng)
        out.s = list(self.s)
        return out

    def jump(self) -> None:
        """Advance the state by 2^64 draws: the streams before and after never overlap within 2^64 draws."""
        acc = [0, 0, 0, 0]
        for word in JUMP:
            for b in range(32):
                if word >> b & 1:
                    acc = [a ^ x for a, x in zip(acc, self.s)]
                self.next_u32()
        self.s = acc

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


def streams(seed: int, count: int) -> list[Prng]:
    """One generator per sample: [Prng(seed), then each 2^64 draws further on]. Twin of streams() in
    web/src/rng/prng.ts."""
    if not (isinstance(count, (int, np.integer)) and count >= 0):
        raise ValueError(f"the stream count must be a non-negative integer, got {count!r}")
    out, g = [], Prng(seed)
    for i in range(int(count)):
        if i:
            g.jump()
        out.append(g.copy())
    return out


def row_normals(source: Prng | list[Prng], rows: int, n: int) -> np.ndarray:
    """[rows, n] normals: from one generator row-major, or row i from source[i] (one stream per sample)."""
    if isinstance(source, Prng):
        return source.normals((rows, n))
    if len(source) != rows:
        raise ValueError(f"{len(source)} streams for {rows} samples")
    return np.stack([g.normals((n,)) for g in source]) if rows else np.zeros((0, n))
