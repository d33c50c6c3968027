#!/usr/bin/python3
"""Writes the images of the media test worlds (issue 12) with the standard library only:
PNGs of 1..4 components and GIFs with a transparent index. The JPEG (photo.jpg) was
written once with stb_image_write (quality 90) from photo_source.png; see README.md."""
import math
import struct
import zlib


def png(path, w, h, channels, pixel):
    """pixel(x, y) -> tuple of `channels` bytes, y from the top row."""
    ctype = {1: 0, 2: 4, 3: 2, 4: 6}[channels]
    raw = b''.join(b'\0' + bytes(c for x in range(w) for c in pixel(x, y)) for y in range(h))

    def chunk(t, d):
        return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, ctype, 0, 0, 0)) +
                chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b''))


def gif(path, w, h, palette, index, transparent=None):
    """An 8-bit GIF89a; LZW codes are 9 bits wide, with a clear code every 250 pixels so the
    table never grows (valid, if not small)."""
    palette = (palette + [(0, 0, 0)] * 256)[:256]
    out = bytearray(b'GIF89a' + struct.pack('<HHBBB', w, h, 0xF7, 0, 0))
    for c in palette:
        out += bytes(c)
    if transparent is not None:
        out += bytes([0x21, 0xF9, 4, 1, 0, 0, transparent, 0])
    out += b',' + struct.pack('<HHHHB', 0, 0, w, h, 0) + bytes([8])
    codes = [256]
    pixels = [index(x, y) for y in range(h) for x in range(w)]
    for i, p in enumerate(pixels):
        if i and i % 250 == 0:
            codes.append(256)
        codes.append(p)
    codes.append(257)
    bits, nbits, data = 0, 0, bytearray()
    for c in codes:
        bits |= c << nbits
        nbits += 9
        while nbits >= 8:
            data.append(bits & 255)
            bits >>= 8
            nbits -= 8
    if nbits:
        data.append(bits & 255)
    for i in range(0, len(data), 255):
        block = data[i:i + 255]
        out += bytes([len(block)]) + block
    out += b'\0;'
    with open(path, 'wb') as f:
        f.write(out)


def checker(x, y, n=8):
    return ((x // n) + (y // n)) % 2


# Textures of 1..4 components (6.22, table 4.6), 32 x 32.
png('grey.png', 32, 32, 1, lambda x, y: (255 if checker(x, y) else 96,))
png('grey_alpha.png', 32, 32, 2, lambda x, y: (255, 255 if checker(x, y) else 0))
png('rgb.png', 32, 32, 3, lambda x, y: (40, 160, 255) if checker(x, y) else (255, 200, 40))
png('rgba.png', 32, 32, 4, lambda x, y: (255, 60, 60, 255) if x < 16 else (60, 255, 60, 96))
gif('stripes.gif', 32, 32, [(255, 255, 255), (200, 0, 160), (0, 0, 0)],
    lambda x, y: 0 if (x // 4) % 2 else (1 if y < 16 else 2), transparent=0)
png('photo_source.png', 32, 32, 3,
    lambda x, y: (int(255 * x / 31), int(255 * y / 31), int(128 + 127 * math.sin(x / 4.0))))


# Background panorama: each face a coloured "hills" silhouette at the bottom (opaque) under
# a transparent sky, with a label bar at the top-left so the orientation shows.
def face(color, label):
    def pixel(x, y):
        if 4 <= x < 4 + 8 * label and 4 <= y < 10 and (x - 4) % 8 < 6:
            return (255, 255, 255, 255)
        hill = 40 + 12 * math.sin(x / 64.0 * 2 * math.pi * 2)
        if y > hill:
            shade = 0.6 + 0.4 * (64 - y) / 24
            return tuple(min(255, int(c * shade)) for c in color) + (255,)
        return (0, 0, 0, 0)
    return pixel


faces = {'front': ((220, 60, 60), 1), 'back': ((60, 200, 60), 2), 'right': ((220, 200, 60), 4)}
for name, (color, label) in faces.items():
    png('bg_%s.png' % name, 64, 64, 4, face(color, label))
# The left face as a GIF with a transparent index (the label as palette index 2).
left = face((60, 60, 220), 3)
gif('bg_left.gif', 64, 64, [(0, 0, 0), (60, 60, 200), (255, 255, 255)],
    lambda x, y: 2 if left(x, y)[:3] == (255, 255, 255) else (1 if left(x, y)[3] else 0),
    transparent=0)
# Top: a grey (1-component) sun pattern, opaque; bottom: grey + alpha ring.
png('bg_top.png', 64, 64, 1,
    lambda x, y: (255 if math.hypot(x - 32, y - 32) < 10 else 150 if (x // 8 + y // 8) % 2 else 110,))
png('bg_bottom.png', 64, 64, 2,
    lambda x, y: (200, 255 if 14 < math.hypot(x - 32, y - 32) < 24 else 0))
