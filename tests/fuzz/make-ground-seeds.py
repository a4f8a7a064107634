#!/usr/bin/env python3
"""Writes a few valid ground tiles (.qvg, docs/formats.md "Ground tile", version 1) as seeds of
fuzz_ground_tile, until quakeview-prep's own ground files join them (make-seeds.sh).

Written from the specification, not with the codec, so the seeds also check that the document
and engine/format agree: each one must decode (fuzz_ground_tile accepts them as they are).

    usage: make-ground-seeds.py OUT_DIR
"""
import math
import os
import struct
import sys
import zlib

VERSION = 1
FLAG_WIDE_INDICES = 1
HEADER_SIZE = 56
SECTION_ENTRY_SIZE = 12

# GroundClass and GroundLabelKind values (engine/format/include/qv/format/GroundTile.h).
LAND, GREEN, FOREST, PARK, WATER, PATH, RAIL, STREET, MAJOR, MOTORWAY = range(10)
STREET_LABEL, WATER_LABEL, PARK_LABEL, NEIGHBOURHOOD_LABEL, SETTLEMENT_LABEL = range(5)


def pad4(data):
    return data + b"\0" * (-len(data) % 4)


def quantize(v, extent):
    return max(0, min(65535, round(v / extent * 65535.0)))


def ground_tile(origin, extent, vertices, runs, labels):
    """runs: [(class, [(a, b, c), ...]), ...] in increasing class order; labels: [(kind, rank, x, y,
    angle, length, text), ...]."""
    wide = len(vertices) > 65535
    vert = b"".join(struct.pack("<HH", quantize(x, extent), quantize(y, extent)) for x, y in vertices)
    index = "<I" if wide else "<H"
    tris = b""
    run_records = b""
    first = 0
    for ground_class, triangles in runs:
        for triangle in triangles:
            tris += b"".join(struct.pack(index, i) for i in triangle)
        run_records += struct.pack("<BII", ground_class, first, len(triangles))
        first += len(triangles)
    labl = b""
    for kind, rank, x, y, angle, length, text in labels:
        encoded = text.encode("utf-8")
        labl += struct.pack("<BBHHffB", kind, rank, quantize(x, extent), quantize(y, extent), angle, length,
                            len(encoded)) + encoded
    sections = [(b"VERT", vert), (b"TRIS", tris), (b"RUNS", run_records), (b"LABL", labl)]
    table = b""
    body = b""
    offset = HEADER_SIZE + SECTION_ENTRY_SIZE * len(sections)
    for name, data in sections:
        table += name + struct.pack("<II", offset + len(body), len(data))
        body += pad4(data)
    after_crc = struct.pack("<IIIHHddfI", len(vertices), first, len(labels), len(runs), len(sections), origin[0],
                            origin[1], extent, 0) + table + body
    size = 16 + len(after_crc)
    flags = FLAG_WIDE_INDICES if wide else 0
    return b"QVGT" + struct.pack("<HHII", VERSION, flags, size, zlib.crc32(after_crc)) + after_crc


def grid_park(n, extent):
    """An n x n grid of vertices over the cell, two park triangles per square."""
    step = extent / (n - 1)
    vertices = [(i * step, j * step) for j in range(n) for i in range(n)]
    triangles = []
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i
            triangles += [(a, a + 1, a + n + 1), (a, a + n + 1, a + n)]
    return vertices, triangles


def seeds():
    yield "street-and-name.qvg", ground_tile((100.0, 200.0), 10.0, [(0, 0), (10, 0), (0, 10)],
                                             [(STREET, [(0, 1, 2)])], [(STREET_LABEL, 5, 2.5, 7.5, 0.5, 8.0, "Elm")])
    yield "empty.qvg", ground_tile((0.0, 0.0), 600.0, [], [], [])
    vertices, park = grid_park(6, 600.0)
    base = len(vertices)
    vertices += [(0, 300), (600, 300), (600, 312), (0, 312), (300, 0), (310, 0), (310, 600), (300, 600)]
    runs = [(PARK, park), (WATER, [(base, base + 1, base + 2), (base, base + 2, base + 3)]),
            (MAJOR, [(base + 4, base + 5, base + 6), (base + 4, base + 6, base + 7)])]
    labels = [(SETTLEMENT_LABEL, 0, 300, 300, 0.0, 0.0, "東京"),
              (STREET_LABEL, 40, 305, 450, math.pi / 2, 290.0, "Avenue of the Americas"),
              (WATER_LABEL, 90, 150, 306, 0.0, 580.0, "Straße am Wasser"),
              (PARK_LABEL, 120, 150, 150, 0.0, 0.0, "Jardin du Luxembourg"),
              (NEIGHBOURHOOD_LABEL, 200, 450, 450, -0.25, 0.0, "Hell's Kitchen")]
    yield "park-river-street.qvg", ground_tile((-1200.0, 600.0), 600.0, vertices, runs, labels)
    every = [(c, [(0, 1, 2)]) for c in range(10)]
    yield "every-class.qvg", ground_tile((-5.0e6, 5.0e6), 1.0e5, [(0, 0), (1e5, 0), (0, 1e5)], every,
                                         [(k, k, 5e4, 5e4, 0.1 * k, 10.0 * k, "label %d" % k) for k in range(5)])


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    os.makedirs(sys.argv[1], exist_ok=True)
    for name, data in seeds():
        with open(os.path.join(sys.argv[1], name), "wb") as f:
            f.write(data)


if __name__ == "__main__":
    main()
