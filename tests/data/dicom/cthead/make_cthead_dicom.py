#!/usr/bin/python3
"""Writes tests/data/dicom/cthead/: the corpus's CThead (../shared/corpus/volume/cthead, the
paper's benchmark: Stanford volume data archive, courtesy UNC Chapel Hill) as DICOM, for the
series, spacing, rescale and compression tests and the README picture.

  series/    29 CT slices of 128 x 128 (CThead averaged 2 x 2 in-plane, every 4th slice),
             JPEG-LS lossless (gdcmconv --jpegls), file names in shuffled order. Pixel
             Spacing 2\\2 mm, Image Position (Patient) z = -8 k mm for CThead slice 4k (the
             top of the head first, highest), Slice Thickness 1 mm on purpose (the reader
             must take the 8 mm position step). Stored = CThead value, Rescale Intercept
             -1024, so value = CThead - 1024. Window presets 40/400 and 1000/2500.
  multiframe.dcm  the first 8 slices of the same at 64 x 64 (4 x 4 averaged) as one
             multi-frame CT file (Number of Frames 8, Spacing Between Slices 8), RLE
             (gdcmconv --rle; gdcmconv makes it an Enhanced CT Image).
  mixed/     a.dcm, b.dcm (32 x 32) and c.dcm (16 x 16) of one series: the size error.

Needs python3-pydicom, python3-numpy and libgdcm-tools (gdcmconv; it also installs
pvrg-jpeg, which GDCM then runs on JPEG data libjpeg rejects: docs/volumes.md; remove both
afterwards). Run from anywhere:
  /usr/bin/python3 tests/data/dicom/cthead/make_cthead_dicom.py
"""
import gzip
import os
import random
import subprocess
import sys

import numpy as np
import pydicom
from pydicom.dataset import Dataset, FileDataset, FileMetaDataset
from pydicom.uid import ExplicitVRLittleEndian, RLELossless

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "..", "..", "..", "..", "..", "shared", "corpus", "volume", "cthead")
ROOT = "1.2.826.0.1.3680043.10.1042."  # a private UID root for these test files


def cthead():
    raw = gzip.open(os.path.join(CORPUS, "CThead.raw.gz")).read()
    return np.frombuffer(raw, dtype=">i2").reshape(113, 256, 256).astype(np.int32)


def base_dataset(name, series_uid, rows, cols):
    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID = "1.2.840.10008.5.1.4.1.1.2"  # CT Image Storage
    meta.MediaStorageSOPInstanceUID = ROOT + name
    meta.TransferSyntaxUID = ExplicitVRLittleEndian
    ds = FileDataset(None, {}, file_meta=meta, preamble=b"\0" * 128)
    ds.SOPClassUID = meta.MediaStorageSOPClassUID
    ds.SOPInstanceUID = meta.MediaStorageSOPInstanceUID
    ds.Modality = "CT"
    ds.PatientName = "CThead^UNC"
    ds.PatientID = "CTHEAD"
    ds.StudyInstanceUID = ROOT + "1"
    ds.SeriesInstanceUID = series_uid
    ds.Rows, ds.Columns = rows, cols
    ds.SamplesPerPixel = 1
    ds.PhotometricInterpretation = "MONOCHROME2"
    ds.BitsAllocated, ds.BitsStored, ds.HighBit = 16, 16, 15
    ds.PixelRepresentation = 1
    ds.RescaleIntercept, ds.RescaleSlope, ds.RescaleType = "-1024", "1", "HU"
    ds.WindowCenter = ["40", "1000"]
    ds.WindowWidth = ["400", "2500"]
    ds.WindowCenterWidthExplanation = ["SOFT TISSUE", "BONE"]
    ds.ImageOrientationPatient = ["1", "0", "0", "0", "1", "0"]
    ds.is_little_endian, ds.is_implicit_VR = True, False
    return ds


def compress(path, flag):
    subprocess.run(["gdcmconv", flag, path, path], check=True)


def main():
    v = cthead()
    out = os.path.join(HERE, "series")
    os.makedirs(out, exist_ok=True)
    for f in os.listdir(out):
        os.remove(os.path.join(out, f))
    half = v.reshape(113, 128, 2, 128, 2).mean(axis=(2, 4)).round().astype(np.int16)
    picks = list(range(0, 113, 4))
    names = [f"IM{n:04d}.dcm" for n in random.Random(42).sample(range(1000, 10000), len(picks))]
    for k, (z, name) in enumerate(zip(picks, names)):
        ds = base_dataset(f"2.{z}", ROOT + "2", 128, 128)
        ds.InstanceNumber = str(k + 1)
        ds.ImagePositionPatient = ["-127", "-127", f"{-2.0 * z + 0.0:g}"]
        ds.PixelSpacing = ["2", "2"]
        ds.SliceThickness = "1"
        ds.PixelData = half[z].tobytes()
        path = os.path.join(out, name)
        ds.save_as(path, write_like_original=False)
        compress(path, "--jpegls")
    quarter = v.reshape(113, 64, 4, 64, 4).mean(axis=(2, 4)).round().astype(np.int16)
    ds = base_dataset("3", ROOT + "3", 64, 64)
    ds.NumberOfFrames = 8
    ds.ImagePositionPatient = ["-126", "-126", "0"]
    ds.PixelSpacing = ["4", "4"]
    ds.SliceThickness = "8"
    ds.SpacingBetweenSlices = "8"
    ds.PixelData = quarter[0:32:4].tobytes()
    path = os.path.join(HERE, "multiframe.dcm")
    ds.compress(RLELossless)  # pydicom's encoder: keeps the CT Image Storage SOP class
    ds.save_as(path, write_like_original=False)
    # mixed/: one series (one Series Instance UID) whose slices differ in size: a.dcm and
    # b.dcm 32 x 32, c.dcm 16 x 16 (CThead slices 40, 48, 56 averaged 8 x 8 and 16 x 16).
    mixed = os.path.join(HERE, "mixed")
    os.makedirs(mixed, exist_ok=True)
    for k, (name, n) in enumerate([("a.dcm", 32), ("b.dcm", 32), ("c.dcm", 16)]):
        f = 256 // n
        img = v[40 + 8 * k].reshape(n, f, n, f).mean(axis=(1, 3)).round().astype(np.int16)
        ds = base_dataset(f"4.{k}", ROOT + "4", n, n)
        ds.ImagePositionPatient = ["0", "0", str(-16 * k)]
        ds.PixelSpacing = [str(f), str(f)]
        ds.PixelData = img.tobytes()
        ds.save_as(os.path.join(mixed, name), write_like_original=False)


if __name__ == "__main__":
    sys.exit(main())
