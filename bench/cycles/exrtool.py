#!/usr/bin/env python3
"""exrtool.py: the little image handling bench/cycles needs, in plain Python 3 (no packages).

Reads scanline OpenEXR files (compression NONE, RLE, ZIPS or ZIP; HALF, FLOAT or UINT channels): what
restir writes (RLE, float) and what build_scene.py makes Blender write (NONE, float). Computes the
project's relMSE (src/metrics/metrics.c: mean over pixels and the 3 channels of
(I - R)^2 / (R^2 + 1e-3)) and writes sRGB PNGs for looking at images.

    exrtool.py relmse IMAGE.exr REF.exr
    exrtool.py png IMAGE.exr OUT.png [EXPOSURE]
    exrtool.py stats IMAGE.exr
"""
import array
import struct
import sys
import zlib

RELMSE_EPS = 1e-3  # src/metrics/metrics.c


class Image:
    def __init__(self, width, height, rgb):
        self.width, self.height, self.rgb = width, height, rgb  # rgb: flat list, 3 per pixel, row 0 on top


def _read_attrs(data):
    if data[:4] != b"\x76\x2f\x31\x01":
        raise ValueError("not an OpenEXR file")
    version = struct.unpack_from("<I", data, 4)[0]
    if version & 0x200 or version & 0x1000:
        raise ValueError("tiled or multi-part OpenEXR files are not read here")
    pos, attrs = 8, {}
    while data[pos] != 0:
        end = data.index(b"\0", pos)
        name = data[pos:end].decode()
        pos = end + 1
        end = data.index(b"\0", pos)
        kind = data[pos:end].decode()
        pos = end + 1
        size = struct.unpack_from("<i", data, pos)[0]
        pos += 4
        attrs[name] = (kind, data[pos:pos + size])
        pos += size
    return attrs, pos + 1


def _channels(raw):
    out, pos = [], 0
    while raw[pos] != 0:
        end = raw.index(b"\0", pos)
        name = raw[pos:end].decode()
        ptype, _, xs, ys = struct.unpack_from("<iIii", raw, end + 1)
        if xs != 1 or ys != 1:
            raise ValueError("subsampled channels are not read here")
        out.append((name, ptype))
        pos = end + 1 + 16
    return out


def _rle_decode(src):
    out = bytearray()
    i, n = 0, len(src)
    while i < n:
        count = struct.unpack_from("b", src, i)[0]
        i += 1
        if count < 0:
            out += src[i:i - count]
            i -= count
        else:
            out += src[i:i + 1] * (count + 1)
            i += 1
    return out


def _unpredict(buf):
    """OpenEXR's RLE / ZIP preprocessing undone: the byte deltas, then the two halves interleaved."""
    t = bytearray(buf)
    prev = t[0] if t else 0
    for i in range(1, len(t)):
        prev = (t[i] + prev - 128) & 0xFF
        t[i] = prev
    half = (len(t) + 1) // 2
    out = bytearray(len(t))
    out[0::2] = t[:half]
    out[1::2] = t[half:]
    return out


def read_exr(path):
    with open(path, "rb") as f:
        data = f.read()
    attrs, pos = _read_attrs(data)
    chans = _channels(attrs["channels"][1])
    compression = attrs["compression"][1][0]
    xmin, ymin, xmax, ymax = struct.unpack("<iiii", attrs["dataWindow"][1])
    width, height = xmax - xmin + 1, ymax - ymin + 1
    lines_per_block = {0: 1, 1: 1, 2: 1, 3: 16}.get(compression)
    if lines_per_block is None:
        raise ValueError(f"{path}: compression {compression} is not read here (NONE, RLE, ZIPS, ZIP are)")
    nblocks = (height + lines_per_block - 1) // lines_per_block
    offsets = struct.unpack_from(f"<{nblocks}Q", data, pos)
    sizes = {0: 4, 1: 2, 2: 4}
    codes = {0: "I", 1: "e", 2: "f"}
    names = [c[0] for c in chans]
    want = []
    for c in "RGB":
        if c in names:
            want.append(names.index(c))
        elif "Y" in names:
            want.append(names.index("Y"))
        else:
            raise ValueError(f"{path}: no {c} channel (has {', '.join(names)})")
    rgb = [0.0] * (3 * width * height)
    line_bytes = sum(sizes[p] for _, p in chans) * width
    for off in offsets:
        y0, size = struct.unpack_from("<ii", data, off)
        block = data[off + 8:off + 8 + size]
        nlines = min(lines_per_block, ymax + 1 - y0)
        expect = line_bytes * nlines
        if compression != 0 and size < expect:
            block = _unpredict(_rle_decode(block) if compression == 1 else zlib.decompress(block))
        if len(block) != expect:
            raise ValueError(f"{path}: block at line {y0} has {len(block)} bytes, {expect} expected")
        p = 0
        for ly in range(nlines):
            row = y0 - ymin + ly
            values = []
            for _, ptype in chans:
                n = sizes[ptype] * width
                if ptype == 1:
                    values.append(struct.unpack_from(f"<{width}e", block, p))
                else:
                    a = array.array(codes[ptype])
                    a.frombytes(bytes(block[p:p + n]))
                    if sys.byteorder != "little":
                        a.byteswap()
                    values.append(a)
                p += n
            base = 3 * width * row
            for k, ci in enumerate(want):
                rgb[base + k:base + 3 * width:3] = [float(v) for v in values[ci]]
    return Image(width, height, rgb)


def relmse(img, ref):
    if (img.width, img.height) != (ref.width, ref.height):
        raise ValueError(f"sizes differ: {img.width}x{img.height} vs {ref.width}x{ref.height}")
    s = 0.0
    for a, r in zip(img.rgb, ref.rgb):
        d = a - r
        s += d * d / (r * r + RELMSE_EPS)
    return s / len(ref.rgb)


def channel_means(img):
    return [sum(img.rgb[c::3]) / (img.width * img.height) for c in range(3)]


def _srgb(v):
    v = max(0.0, min(1.0, v))
    return 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055


def write_png(path, width, height, rgb, scale=1.0):
    """rgb: flat linear RGB (row 0 on top), written sRGB-encoded and clamped after multiplying by scale."""
    lut_n = 4096
    lut = bytes(round(255 * _srgb(i / (lut_n - 1))) for i in range(lut_n))
    raw = bytearray()
    for y in range(height):
        raw.append(0)
        row = rgb[3 * width * y:3 * width * (y + 1)]
        raw += bytes(lut[min(lut_n - 1, max(0, int(v * scale * (lut_n - 1) + 0.5)))] if v == v else 0 for v in row)

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(bytes(raw), 6)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    cmd = sys.argv[1]
    if cmd == "relmse" and len(sys.argv) == 4:
        print(f"{relmse(read_exr(sys.argv[2]), read_exr(sys.argv[3])):.6g}")
    elif cmd == "png" and len(sys.argv) in (4, 5):
        img = read_exr(sys.argv[2])
        write_png(sys.argv[3], img.width, img.height, img.rgb, float(sys.argv[4]) if len(sys.argv) == 5 else 1.0)
    elif cmd == "stats" and len(sys.argv) == 3:
        img = read_exr(sys.argv[2])
        print(f"{img.width}x{img.height} mean RGB " + " ".join(f"{m:.6g}" for m in channel_means(img)))
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
