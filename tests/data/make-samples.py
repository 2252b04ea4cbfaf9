#!/usr/bin/env python3
"""Writes the sample MLCP files of tests/data from docs/mlcp-format.md alone.

This is a second, independent writer of format version 1: tests/unit/test_io_samples.cpp
checks that the C++ reader accepts its files and that the C++ writer reproduces them byte
for byte. Run it from anywhere; it writes next to itself:

    python3 tests/data/make-samples.py
"""
import math
import os
import struct
import zlib

MAGIC = b"ODEBPPMLCP\0"
VERSION = 1
HAS_FINDEX, HAS_BLOCKS, HAS_X, HAS_META = 1, 2, 4, 8
INF = math.inf


def encode(A, b, lo, hi, nub, findex=None, block_row=None, block_body=None, num_bodies=0,
           x=None, meta=None):
    """A is a full n x n list of rows; only its lower triangle is written."""
    n = len(b)
    meta_text = "".join(f"{k}={v}\n" for k, v in (meta or [])).encode("utf-8")
    flags = ((HAS_FINDEX if findex is not None else 0) | (HAS_BLOCKS if block_row is not None else 0)
             | (HAS_X if x is not None else 0) | (HAS_META if meta_text else 0))
    num_blocks = len(block_row) - 1 if block_row is not None else 0
    out = bytearray(MAGIC)
    out += struct.pack("<7I", VERSION, flags, n, nub, num_blocks, num_bodies, len(meta_text))
    out += b"\0"  # reserved
    assert len(out) == 40
    for i in range(n):
        out += struct.pack(f"<{i + 1}d", *A[i][: i + 1])
    for v in (b, lo, hi):
        out += struct.pack(f"<{n}d", *v)
    if findex is not None:
        out += struct.pack(f"<{n}i", *findex)
    if block_row is not None:
        out += struct.pack(f"<{num_blocks + 1}i", *block_row)
        out += struct.pack(f"<{2 * num_blocks}i", *block_body)
    if x is not None:
        out += struct.pack(f"<{n}d", *x)
    out += meta_text
    out += struct.pack("<I", zlib.crc32(bytes(out)) & 0xFFFFFFFF)
    return bytes(out)


def solve_dense(A, b):
    """Gaussian elimination with partial pivoting (the samples are small and well conditioned)."""
    n = len(b)
    M = [row[:] + [b[i]] for i, row in enumerate(A)]
    for k in range(n):
        p = max(range(k, n), key=lambda r: abs(M[r][k]))
        M[k], M[p] = M[p], M[k]
        for r in range(k + 1, n):
            f = M[r][k] / M[k][k]
            for c in range(k, n + 1):
                M[r][c] -= f * M[k][c]
    x = [0.0] * n
    for k in reversed(range(n)):
        x[k] = (M[k][n] - sum(M[k][c] * x[c] for c in range(k + 1, n))) / M[k][k]
    return x


def notes_friction_example():
    """The 3-row problem of docs/maths.md (Dantzig's friction semantics): one contact normal and two friction rows, mu = 0.5."""
    A = [[2.0, 0.3, 0.1], [0.3, 1.5, 0.2], [0.1, 0.2, 1.8]]
    return encode(A, b=[1.0, 0.9, -0.2], lo=[0.0, -0.5, -0.5], hi=[INF, 0.5, 0.5], nub=0,
                  findex=[-1, 0, 0], meta=[("scene", "notes-friction-example"), ("source", "docs/maths.md")])


def ball_chain():
    """A pendulum chain of 4 point masses hung by ball joints (3 rows each) from the ground:
    A = J M^-1 J^T + cfm I, joint k couples bodies k-1 and k (body -1: the ground).
    All rows are equalities, so x = A^-1 b is the solution and is stored as the reference."""
    bodies, cfm = 4, 1e-6
    inv_mass = [1.0, 0.5, 0.25, 0.02]  # 1, 2, 4 and 50 kg: a heavy load at the end
    n = 3 * bodies
    # J[row][3 * body + axis]: joint k pulls body k with +I and body k-1 with -I
    J = [[0.0] * (3 * bodies) for _ in range(n)]
    for k in range(bodies):
        for axis in range(3):
            J[3 * k + axis][3 * k + axis] = 1.0
            if k > 0:
                J[3 * k + axis][3 * (k - 1) + axis] = -1.0
    A = [[sum(J[i][c] * inv_mass[c // 3] * J[j][c] for c in range(3 * bodies)) + (cfm if i == j else 0.0)
          for j in range(n)] for i in range(n)]
    b = [(-9.81 * 0.01 if i % 3 == 2 else 0.0) + 0.001 * i for i in range(n)]
    block_row = [3 * k for k in range(bodies + 1)]
    block_body = []
    for k in range(bodies):
        block_body += [k, k - 1]
    return encode(A, b, lo=[-INF] * n, hi=[INF] * n, nub=n, findex=[-1] * n, block_row=block_row,
                  block_body=block_body, num_bodies=bodies, x=solve_dense(A, b),
                  meta=[("scene", "ball-chain"), ("cfm", "9.9999999999999995e-07"), ("step_size", "0.01")])


def box_contact():
    """One box resting on the ground on 4 contacts with pyramid friction (12 rows), and a
    bounded motor row: every kind of bound, findex and a single block per contact."""
    contacts = 4
    n = 3 * contacts + 1
    A = [[(4.0 if i == j else 1.0 / (1.0 + abs(i - j))) for j in range(n)] for i in range(n)]
    b, lo, hi, findex = [], [], [], []
    for c in range(contacts):
        b += [0.1 + 0.01 * c, 0.02, -0.03]
        lo += [0.0, -0.8, -0.8]
        hi += [INF, 0.8, 0.8]
        findex += [-1, 3 * c, 3 * c]
    b.append(0.5)
    lo.append(-0.25)
    hi.append(0.25)
    findex.append(-1)
    block_row = [3 * c for c in range(contacts)] + [3 * contacts, n]
    block_body = [0, -1] * contacts + [0, -1]
    return encode(A, b, lo, hi, nub=0, findex=findex, block_row=block_row, block_body=block_body,
                  num_bodies=1, meta=[("scene", "box-contact"), ("frame", "0"), ("island", "0")])


def never_slipping():
    """The friction example with mu = +inf (ODE's dInfinity, "never slips": lo = -mu, hi = mu):
    legal input whose friction rows are unbounded (docs/maths.md, Infinite friction)."""
    A = [[2.0, 0.3, 0.1], [0.3, 1.5, 0.2], [0.1, 0.2, 1.8]]
    return encode(A, b=[1.0, 0.9, -0.2], lo=[0.0, -INF, -INF], hi=[INF, INF, INF], nub=0,
                  findex=[-1, 0, 0], meta=[("scene", "never-slipping"), ("source", "docs/maths.md")])


def negative_friction():
    """Illegal: a friction coefficient mu = -inf (hi of a friction row); solve() must refuse it."""
    A = [[2.0, 0.3, 0.1], [0.3, 1.5, 0.2], [0.1, 0.2, 1.8]]
    return encode(A, b=[1.0, 0.9, -0.2], lo=[0.0, INF, -0.5], hi=[INF, -INF, 0.5], nub=0,
                  findex=[-1, 0, 0], meta=[("scene", "negative-friction"), ("expect", "invalid-input")])


def plain_two_rows():
    """No optional section at all."""
    return encode([[1.0, 0.5], [0.5, 2.0]], b=[1.0, -1.0], lo=[0.0, -1.0], hi=[INF, 1.0], nub=0)


def empty_problem():
    return encode([], b=[], lo=[], hi=[], nub=0)


SAMPLES = {
    "notes-friction-3.mlcp": notes_friction_example,
    "ball-chain-12.mlcp": ball_chain,
    "box-contact-13.mlcp": box_contact,
    "never-slipping-3.mlcp": never_slipping,
    "negative-friction-3.mlcp": negative_friction,
    "plain-2.mlcp": plain_two_rows,
    "empty-0.mlcp": empty_problem,
}

if __name__ == "__main__":
    here = os.path.dirname(os.path.abspath(__file__))
    for name, make in SAMPLES.items():
        with open(os.path.join(here, name), "wb") as f:
            f.write(make())
        print(name)
