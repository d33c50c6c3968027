#!/usr/bin/python3
"""Empirical bounds for the QNV entropy coding (docs/qnv-format.md, "What 24 bits would take").

Reads a *plain* .qnv stream (ghostspace encode ... --packet-bytes B, default coding) and prints,
per vector, the empirical entropies (no table cost) of what a packet-independent lossless
coder must send, under stronger and stronger stream-wide models:

  position: the set of each packet's positions, ideally coded among all voxels, among the
            occupied blocks, and under a density prior per block (count of vectors and a
            Gaussian in packet index fitted per block), the model cost not counted;
  magnitude: log2 of each packet's A range (the offsets are uniform in it);
  direction: theta, phi deltas from the block's mean direction (blocks of 2^b), per packet;
  colour: the palette index given the block's mean colour, per packet.

  /usr/bin/python3 tests/bench/qnv_entropy_bounds.py head.qnv [bunny.qnv ...]
Needs numpy (Debian python3-numpy). Prints figures only; tests do not run it.
"""
import math
import struct
import sys

import numpy as np


def load(path):
    b = open(path, 'rb').read()
    header_bytes = struct.unpack_from('<I', b, 100)[0]
    kind, dims = b[10], struct.unpack_from('<3I', b, 80)
    off, recs, pk = header_bytes, [], []
    while off + 16 <= len(b):
        cnt, seq = struct.unpack_from('<HI', b, off + 2)
        payload, enc = struct.unpack_from('<HB', b, off + 8)
        if enc != 0:
            sys.exit(f'{path}: not a plain stream (packet encoding {enc})')
        recs.append(np.frombuffer(b, dtype='<u8', count=cnt, offset=off + 16))
        pk.append(np.full(cnt, seq, dtype=np.int64))
        off += 16 + payload
    r = np.concatenate(recs).astype(np.uint64)
    f = {name: ((r >> np.uint64(shift)) & np.uint64(mask)).astype(np.int64)
         for name, shift, mask in [('X', 54, 1023), ('Y', 44, 1023), ('Z', 34, 1023), ('T', 29, 31),
                                   ('P', 23, 63), ('A', 8, 32767), ('C', 0, 255)]}
    f['pk'] = np.concatenate(pk)
    for axis, d in zip('XYZ', dims):  # voxel indices on a volume's grid, else cells
        if kind == 2 and 2 <= d <= 1024:
            lut = np.full(1024, -1, dtype=np.int64)
            i = np.arange(d)
            lut[np.minimum(i * 1024 // (d - 1), 1023)] = i
            f['I' + axis] = lut[f[axis]]
        else:
            f['I' + axis] = f[axis]
    return f


def entropy(symbols):
    _, c = np.unique(symbols, return_counts=True)
    return float(-(c * np.log2(c / c.sum())).sum())


def spread(v):
    v = v.astype(np.uint64) & np.uint64(0x3ff)
    for shift, mask in [(16, 0x30000ff), (8, 0x300f00f), (4, 0x30c30c3), (2, 0x9249249)]:
        v = (v | (v << np.uint64(shift))) & np.uint64(mask)
    return v


def morton(x, y, z):
    return (spread(x) | (spread(y) << np.uint64(1)) | (spread(z) << np.uint64(2))).astype(np.int64)


def report(path):
    f = load(path)
    n, pk = len(f['A']), f['pk']
    packets = int(pk.max()) + 1
    per_packet = lambda sym: sum(entropy(sym[pk == p]) for p in range(packets)) / n
    log2_fact = lambda k: math.lgamma(k + 1) / math.log(2)
    print(f'== {path}: {n} vectors, {packets} packets ==')
    a_bits = sum(((pk == p).sum()) * math.log2(f['A'][pk == p].max() - f['A'][pk == p].min() + 1)
                 for p in range(packets)) / n
    print(f'  magnitude, uniform in each packet\'s A range: {a_bits:.2f}')
    ix, iy, iz = f['IX'], f['IY'], f['IZ']
    th = (f['T'] + 0.5) * np.pi / 32
    ph = (f['P'] + 0.5) * np.pi / 32
    normals = np.stack([np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)], 1)
    print(f'  direction today (theta, phi as symbols per packet): '
          f'{per_packet(f["T"]) + per_packet(f["P"]):.2f}; colour per packet: {per_packet(f["C"]):.2f}')
    for b in [1, 2, 3, 4]:
        block = morton(ix >> b, iy >> b, iz >> b)
        _, inv = np.unique(block, return_inverse=True)
        blocks = int(inv.max()) + 1
        count = np.bincount(inv).astype(float)
        mean = np.bincount(inv, weights=pk) / count
        sd = np.sqrt(np.maximum(np.bincount(inv, weights=pk * pk) / count - mean * mean, 0)) + 2
        ideal = {'occupied': 0.0, 'count + Gaussian in packet': 0.0}
        for p in range(packets):
            m = pk == p
            k = int(m.sum())
            for name in ideal:
                w = np.ones(blocks) if name == 'occupied' else \
                    count * np.exp(-0.5 * ((p - mean) / sd) ** 2) / sd + 1e-3 * count / count.sum()
                q = w / w.sum()
                ideal[name] += -np.log2(q[inv[m]]).sum() + 3 * b * k - log2_fact(k)
        s = np.zeros((blocks, 3))
        np.add.at(s, inv, normals)
        s /= np.maximum(np.linalg.norm(s, axis=1, keepdims=True), 1e-12)
        bt = np.minimum(np.floor(np.arccos(np.clip(s[:, 2], -1, 1)) / np.pi * 32), 31).astype(np.int64)
        bp = np.floor((np.arctan2(s[:, 1], s[:, 0]) % (2 * np.pi)) / (2 * np.pi) * 64).astype(np.int64) % 64
        direction = per_packet(f['T'] - bt[inv]) + per_packet((f['P'] - bp[inv]) % 64)
        colour_mean = np.round(np.bincount(inv, weights=f['C']) / count).astype(np.int64)
        colour = per_packet(f['C'] - colour_mean[inv])
        print(f'  blocks of {1 << b}^3 ({blocks} occupied): position among occupied '
              f'{ideal["occupied"] / n:.2f}, with density prior {ideal["count + Gaussian in packet"] / n:.2f}; '
              f'direction from block mean {direction:.2f}; colour given block mean {colour:.2f}')


if __name__ == '__main__':
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for path in sys.argv[1:]:
        report(path)
