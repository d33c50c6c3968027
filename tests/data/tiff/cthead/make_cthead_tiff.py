#!/usr/bin/python3
"""Writes tests/data/tiff/cthead/: the corpus's CThead (../shared/corpus/volume/cthead, the
paper's benchmark: Stanford volume data archive, courtesy UNC Chapel Hill) as TIFF, for the
TIFF reader's tests and the README picture.

  cthead.ome.tif  OME-TIFF, 29 pages of 128 x 128 uint16 (CThead averaged 2 x 2 in-plane,
                  every 4th slice), deflate; OME-XML PhysicalSizeX/Y = 2 mm, PhysicalSizeZ
                  = 8 mm (units given, so the reader must convert them: 2000 and 8000 um).
  float32.tif     plain multi-page TIFF, 8 pages of 64 x 64 float32 (CThead averaged 4 x 4,
                  slices 0, 4, ... 28, divided by 1000), no OME-XML.
  slices/         8 single-page 64 x 64 uint8 TIFFs (the same slices / 16), one per file,
                  named z1.tif .. z8.tif (natural order: z2 before z10), a folder stack.

Needs python3-pil and python3-numpy (Debian). Run from anywhere:
  /usr/bin/python3 tests/data/tiff/cthead/make_cthead_tiff.py
"""
import gzip
import os

import numpy as np
from PIL import Image

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "..", "..", "..", "..", "..", "shared", "corpus", "volume", "cthead")

OME = """<?xml version="1.0" encoding="UTF-8"?>
<OME xmlns="http://www.openmicroscopy.org/Schemas/OME/2016-06" \
Creator="make_cthead_tiff.py"><Image ID="Image:0" Name="CThead"><Pixels ID="Pixels:0" \
DimensionOrder="XYZCT" Type="uint16" SizeX="128" SizeY="128" SizeZ="29" SizeC="1" SizeT="1" \
PhysicalSizeX="2" PhysicalSizeXUnit="mm" PhysicalSizeY="2" PhysicalSizeYUnit="mm" \
PhysicalSizeZ="8" PhysicalSizeZUnit="mm"><Channel ID="Channel:0:0" SamplesPerPixel="1"/>\
<TiffData/></Pixels></Image></OME>"""


def main():
    raw = gzip.open(os.path.join(CORPUS, "CThead.raw.gz")).read()
    v = np.frombuffer(raw, dtype=">i2").reshape(113, 256, 256).astype(np.int32)
    half = v.reshape(113, 128, 2, 128, 2).mean(axis=(2, 4)).round().astype(np.uint16)
    pages = [Image.fromarray(half[z], mode="I;16") for z in range(0, 113, 4)]
    pages[0].save(os.path.join(HERE, "cthead.ome.tif"), save_all=True, append_images=pages[1:],
                  compression="tiff_adobe_deflate", description=OME)
    quarter = v.reshape(113, 64, 4, 64, 4).mean(axis=(2, 4))
    floats = [Image.fromarray((quarter[z] / 1000.0).astype(np.float32), mode="F")
              for z in range(0, 32, 4)]
    floats[0].save(os.path.join(HERE, "float32.tif"), save_all=True, append_images=floats[1:])
    slices = os.path.join(HERE, "slices")
    os.makedirs(slices, exist_ok=True)
    for k, z in enumerate(range(0, 32, 4)):
        img = np.clip(quarter[z] / 16.0, 0, 255).round().astype(np.uint8)
        Image.fromarray(img, mode="L").save(os.path.join(slices, f"z{k + 1}.tif"))


if __name__ == "__main__":
    main()
