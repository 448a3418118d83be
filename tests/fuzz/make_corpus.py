#!/usr/bin/env python3
"""Writes the binary seed files of tests/fuzz: PCD and PLY maps, and the PointCloud2 and Image
inputs of the pointcloud2 and panorama fuzzers (their byte layout is in each fuzz_*.cpp). Small
real-looking files, one per format variant; run from anywhere, rewrites them in place."""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def out(target, name, data):
    path = os.path.join(HERE, target, "corpus", name)
    with open(path, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def points(n=24):
    """A few points on a wall and a floor, in metres."""
    pts = []
    for k in range(n):
        a = 2 * math.pi * k / n
        pts.append((4.0 * math.cos(a), 4.0 * math.sin(a), 0.5 * (k % 3) - 0.5))
    return pts


# ---- PCD ----
def pcd_header(fields, sizes, types, counts, n, data):
    return ("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS %s\nSIZE %s\nTYPE %s\nCOUNT %s\n"
            "WIDTH %d\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS %d\nDATA %s\n" %
            (" ".join(fields), " ".join(map(str, sizes)), " ".join(types), " ".join(map(str, counts)), n, n, data))


def lzf_literals(raw):
    """LZF with literal runs only (a control byte < 32: the next ctrl+1 bytes)."""
    out_bytes = bytearray()
    for i in range(0, len(raw), 32):
        chunk = raw[i:i + 32]
        out_bytes.append(len(chunk) - 1)
        out_bytes += chunk
    return bytes(out_bytes)


def lzf_with_references(raw):
    """LZF with back references (a control byte >= 32: length, then distance), greedy over the
    last 8192 bytes, and literal runs between them."""
    out_bytes, literals, i = bytearray(), bytearray(), 0

    def flush():
        for k in range(0, len(literals), 32):
            chunk = literals[k:k + 32]
            out_bytes.append(len(chunk) - 1)
            out_bytes.extend(chunk)
        literals.clear()

    while i < len(raw):
        best_len, best_dist = 0, 0
        for start in range(max(0, i - 8192), i):
            n = 0
            while n < 264 and i + n < len(raw) and raw[start + n] == raw[i + n]:
                n += 1
            if n > best_len:
                best_len, best_dist = n, i - start
        if best_len < 3:
            literals.append(raw[i])
            i += 1
            continue
        flush()
        length, distance = best_len - 2, best_dist - 1
        if length < 7:
            out_bytes.append((length << 5) | (distance >> 8))
        else:
            out_bytes.append((7 << 5) | (distance >> 8))
            out_bytes.append(length - 7)
        out_bytes.append(distance & 0xff)
        i += best_len
    flush()
    return bytes(out_bytes)


def write_pcd():
    pts = points()
    n = len(pts)
    ascii_body = "".join("%g %g %g %g\n" % (x, y, z, 0.5) for x, y, z in pts)
    out("pcd", "ascii_xyzi.pcd", pcd_header(["x", "y", "z", "intensity"], [4] * 4, ["F"] * 4, [1] * 4, n, "ascii")
        + ascii_body)
    binary = b"".join(struct.pack("<fff", *p) for p in pts)
    out("pcd", "binary_xyz.pcd", pcd_header(["x", "y", "z"], [4] * 3, ["F"] * 3, [1] * 3, n, "binary").encode()
        + binary)
    # binary_compressed: fields one after the other (all x, then all y, ...), LZF-compressed.
    soa = b"".join(struct.pack("<%df" % n, *[p[i] for p in pts]) for i in range(3))
    compressed = lzf_literals(soa)
    out("pcd", "compressed_xyz.pcd",
        pcd_header(["x", "y", "z"], [4] * 3, ["F"] * 3, [1] * 3, n, "binary_compressed").encode()
        + struct.pack("<II", len(compressed), len(soa)) + compressed)
    # Doubles, an unsigned rgb and a field with COUNT 2, as other tools write.
    body = b"".join(struct.pack("<dddIff", x, y, z, 0xff8000, 1.0, 2.0) for x, y, z in pts)
    out("pcd", "binary_double_rgb_count2.pcd",
        pcd_header(["x", "y", "z", "rgb", "normal"], [8, 8, 8, 4, 4], ["F", "F", "F", "U", "F"], [1, 1, 1, 1, 2], n,
                   "binary").encode() + body)
    # binary_compressed with back references, x, y, z of SIZE 8 among other fields (an unsigned
    # ring first, an intensity between): the compressed layout's field offsets and LZF's references.
    fields = [("ring", 2, "U", "<%dH", lambda k, p: k % 4), ("x", 8, "F", "<%dd", lambda k, p: p[0]),
              ("intensity", 4, "F", "<%df", lambda k, p: 0.25), ("y", 8, "F", "<%dd", lambda k, p: p[1]),
              ("z", 8, "F", "<%dd", lambda k, p: p[2])]
    soa = b"".join(struct.pack(fmt % n, *[value(k, p) for k, p in enumerate(pts)]) for _, _, _, fmt, value in fields)
    compressed = lzf_with_references(soa)
    out("pcd", "compressed_double_fields_references.pcd",
        pcd_header([f[0] for f in fields], [f[1] for f in fields], [f[2] for f in fields], [1] * len(fields), n,
                   "binary_compressed").encode() + struct.pack("<II", len(compressed), len(soa)) + compressed)
    nan_body = "nan nan nan\n1 2 3\ninf 0 0\n"
    out("pcd", "ascii_non_finite.pcd", pcd_header(["x", "y", "z"], [4] * 3, ["F"] * 3, [1] * 3, 3, "ascii") + nan_body)


# ---- PLY ----
def cube():
    v = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    f = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    return v, f


def write_ply():
    v, f = cube()
    head = "ply\nformat %s 1.0\ncomment uampc fuzz seed\nelement vertex %d\nproperty float x\nproperty float y\n" \
           "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
    body = "".join("%g %g %g\n" % p for p in v) + "".join("4 %d %d %d %d\n" % q for q in f)
    out("ply", "ascii_cube.ply", head % ("ascii", len(v), len(f)) + body)
    for endian, tag in (("<", "binary_little_endian"), (">", "binary_big_endian")):
        data = b"".join(struct.pack(endian + "fff", *p) for p in v)
        data += b"".join(struct.pack(endian + "B4i", 4, *q) for q in f)
        out("ply", tag + "_cube.ply", (head % (tag, len(v), len(f))).encode() + data)
    pts = points()
    head = "ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty double x\nproperty double y\n" \
           "property double z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n"
    out("ply", "binary_points_rgb.ply",
        (head % len(pts)).encode() + b"".join(struct.pack("<dddBBB", x, y, z, 255, 128, 0) for x, y, z in pts))
    head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n" \
           "element face 1\nproperty list uint8 uint32 vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
    out("ply", "ascii_triangle_uint8_uint32.ply", head)


# ---- PointCloud2 (fuzz_pointcloud2.cpp's layout) ----
INT8, UINT8, INT16, UINT16, INT32, UINT32, FLOAT32, FLOAT64 = range(1, 9)


def cloud(fields, point_step, rows, stamp=(100, 0), big_endian=0):
    n = len(rows)
    head = struct.pack("<IIIIBBiIB", 1, n, point_step, point_step * n, big_endian, 1, stamp[0], stamp[1], len(fields))
    for name, offset, datatype in fields:
        head += struct.pack("<B", len(name)) + name.encode() + struct.pack("<IBI", offset, datatype, 1)
    return head + b"".join(rows)


def write_pointcloud2():
    pts = points()
    n = len(pts)
    dt = 0.1 / n
    xyz = [("x", 0, FLOAT32), ("y", 4, FLOAT32), ("z", 8, FLOAT32)]
    out("pointcloud2", "uampc_scan", cloud(xyz + [("intensity", 12, FLOAT32), ("t", 16, FLOAT32), ("ring", 20, UINT16)],
                                           22, [struct.pack("<fffffH", *p, 0.5, k * dt, k % 4) for k, p in enumerate(pts)]))
    out("pointcloud2", "livox_offset_time_ns",
        cloud(xyz + [("intensity", 12, FLOAT32), ("tag", 16, UINT8), ("line", 17, UINT8), ("offset_time", 18, UINT32)],
              22, [struct.pack("<ffffBBI", *p, 10.0, 0, k % 4, int(k * dt * 1e9)) for k, p in enumerate(pts)]))
    out("pointcloud2", "velodyne_time_padded",
        cloud(xyz + [("intensity", 16, FLOAT32), ("ring", 20, UINT16), ("time", 24, FLOAT32)], 32,
              [struct.pack("<fff4xfH2xf4x", *p, 7.0, k % 16, k * dt) for k, p in enumerate(pts)]))
    out("pointcloud2", "timestamp_float64",
        cloud(xyz + [("timestamp", 16, FLOAT64)], 24, [struct.pack("<fff4xd", *p, 100.0 + k * dt) for k, p in
                                                         enumerate(pts)]))
    out("pointcloud2", "xyz_only_registered", cloud(xyz, 12, [struct.pack("<fff", *p) for p in pts]))
    out("pointcloud2", "no_time_field", cloud(xyz + [("intensity", 12, FLOAT32)], 16,
                                              [struct.pack("<ffff", *p, 1.0) for p in pts]))


# ---- Image panoramas (fuzz_panorama.cpp's layout) ----
def image(period, max_range, width, height, step, big_endian, encoding, stamp, data):
    return (struct.pack("<BBIIIB", period, max_range, width, height, step, big_endian)
            + struct.pack("<B", len(encoding)) + encoding.encode() + struct.pack("<iI", *stamp) + data)


def write_panorama():
    w, h = 32, 16
    depth = b"".join(struct.pack("<f", 2.0 + (r * w + c) % 37 if (r + c) % 7 else 0.0)
                     for r in range(h) for c in range(w))
    out("panorama", "depth_32x16", image(0, 0, w, h, 4 * w, 0, "32FC1", (20, 0), depth))
    out("panorama", "depth_fast_snapshots", image(1, 1, w, h, 4 * w, 0, "32FC1", (3, 500000000), depth))
    out("panorama", "mono8", image(0, 0, w, h, w, 0, "mono8", (20, 0), bytes(range(256)) * 2))
    out("panorama", "big_endian", image(0, 2, w, h, 4 * w, 1, "32FC1", (40, 0), depth))
    nan_inf = b"".join(struct.pack("<f", v) for v in (float("nan"), float("inf"), -1.0, 1e30) * 4)
    out("panorama", "non_finite_4x4", image(0, 0, 4, 4, 16, 0, "32FC1", (20, 0), nan_inf))
    # A stamp 2^31 s ahead at the 1 ms snapshot period: the evaluator once stepped there one
    # period at a time (a CI timeout).
    out("panorama", "far_future_stamp", image(2, 0, 4, 4, 16, 0, "32FC1", (2**31 - 1, 0), nan_inf))


if __name__ == "__main__":
    write_pcd()
    write_ply()
    write_pointcloud2()
    write_panorama()
