#!/usr/bin/python3
"""Writes tests/data/vdb/: corpus data as OpenVDB grids, for the OpenVDB reader's tests and
the README picture (issue 42). Real data turned into VDB by OpenVDB 10's own Python binding:

  cthead_fog.vdb   a fog volume (GRID_FOG_VOLUME, float grid "density") of the corpus's
                   CThead (../shared/corpus/volume/cthead, the paper's benchmark: Stanford
                   volume data archive, courtesy UNC Chapel Hill) averaged 4 x 4 in-plane,
                   every 4th slice: 64 x 64 x 29 voxels of 4 x 4 x 8 mm (a linear
                   transform with that scale), density = CT value / 3000 clamped to [0, 1];
                   voxels under 0.1 (air) inactive, so the grid is sparse.
  cthead_skin_ls.vdb
                   a narrow-band level set (GRID_LEVEL_SET, float grid "ls_skin", half
                   width 3 voxels of 4 mm) of CThead's skin: the isosurface at density 0.3
                   of cthead_fog.vdb (OpenVDB's volumeToMesh, a closed surface) turned into
                   a level set by OpenVDB's meshToLevelSet; plus a vec3s grid "v" before
                   it, so that the reader must skip a grid it cannot show. (The corpus's
                   bunny is not watertight: its level set has no inside.)

It also writes the seeds of fuzz_vdb (tests/fuzz/seeds/vdb/): a small fog sphere and a small
level-set sphere, each under 64 KiB.

Needs python3-openvdb and python3-numpy (Debian). Run from anywhere:
  /usr/bin/python3 tests/data/vdb/make_vdb.py
"""
import gzip
import os

import numpy as np
import pyopenvdb as vdb

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "..", "..", "..", "..", "shared", "corpus")


def cthead():
    raw = gzip.open(os.path.join(CORPUS, "volume", "cthead", "CThead.raw.gz")).read()
    v = np.frombuffer(raw, dtype=">i2").reshape(113, 256, 256).astype(np.float32)
    small = v[::4].reshape(29, 64, 4, 64, 4).mean(axis=(2, 4))  # z, y, x
    density = np.clip(small / 3000.0, 0.0, 1.0).astype(np.float32)
    density[density < 0.1] = 0.0
    grid = vdb.FloatGrid()
    grid.copyFromArray(np.ascontiguousarray(density.transpose(2, 1, 0)), ijk=(0, 0, 0),
                       tolerance=0.0)
    grid.name = "density"
    grid.gridClass = vdb.GridClass.FOG_VOLUME
    grid.transform = vdb.createLinearTransform(
        [[4, 0, 0, 0], [0, 4, 0, 0], [0, 0, 8, 0], [0, 0, 0, 1]])
    vdb.write(os.path.join(HERE, "cthead_fog.vdb"), grids=[grid])


def skin():
    grid = vdb.read(os.path.join(HERE, "cthead_fog.vdb"), "density")
    points, triangles, quads = grid.convertToPolygons(isovalue=0.3)
    ls = vdb.FloatGrid.createLevelSetFromPolygons(
        points, triangles=triangles, quads=quads,
        transform=vdb.createLinearTransform(voxelSize=4.0), halfWidth=3.0)
    ls.name = "ls_skin"
    v = vdb.Vec3SGrid()
    v.name = "v"
    v.fill((0, 0, 0), (3, 3, 3), (1, 0, 0))
    vdb.write(os.path.join(HERE, "cthead_skin_ls.vdb"), grids=[v, ls])


def seeds():
    out = os.path.join(HERE, "..", "..", "fuzz", "seeds", "vdb")
    os.makedirs(out, exist_ok=True)
    i, j, k = np.mgrid[0:8, 0:8, 0:8]
    fog = np.clip(1.0 - np.sqrt((i - 3.5) ** 2 + (j - 3.5) ** 2 + (k - 3.5) ** 2) / 4.0, 0, 1)
    grid = vdb.FloatGrid()
    grid.copyFromArray(fog.astype(np.float32), ijk=(0, 0, 0), tolerance=0.0)
    grid.name = "density"
    grid.gridClass = vdb.GridClass.FOG_VOLUME
    vdb.write(os.path.join(out, "fog_ball.vdb"), grids=[grid])
    # A level set of the same ball: signed distance in voxels, narrow band of 1.5.
    sdf = np.sqrt((i - 3.5) ** 2 + (j - 3.5) ** 2 + (k - 3.5) ** 2) - 2.5
    ls = vdb.FloatGrid(1.5)
    ls.copyFromArray(np.clip(sdf, -1.5, 1.5).astype(np.float32), ijk=(0, 0, 0), tolerance=0.0)
    ls.name = "ball"
    ls.gridClass = vdb.GridClass.LEVEL_SET
    vdb.write(os.path.join(out, "ball_ls.vdb"), grids=[ls])


if __name__ == "__main__":
    cthead()
    skin()
    seeds()
