"""What the core tests share: where things are, stand-in executables, a PNG reader."""

import os
import stat
import struct
import sys
import time
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ADDON_ROOT = os.path.dirname(os.path.dirname(HERE))     # exporters/blender: holds facet_blender/
REPO = os.path.dirname(os.path.dirname(ADDON_ROOT))
if ADDON_ROOT not in sys.path:
    sys.path.insert(0, ADDON_ROOT)


def example(*parts):
    """A file of the repository's examples/ folder."""
    return os.path.join(REPO, "examples", *parts)


def script(path, text):
    """An executable shell script at `path` (a stand-in for facet or POV-Ray)."""
    with open(path, "w") as f:
        f.write("#!/bin/sh\n" + text)
    os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)
    return str(path)


def read_png(path):
    """(width, height, bit depth, samples) of a non-interlaced RGB PNG, samples as a flat
    list of integers, top row first. Written independently of core/pov.py's writer."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        chunk = data[pos + 8:pos + 8 + length]
        crc = struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])[0]
        assert zlib.crc32(kind + chunk) & 0xFFFFFFFF == crc, f"{path}: bad CRC in {kind}"
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", chunk)
        elif kind == b"IDAT":
            idat += chunk
        pos += 12 + length
    width, height, depth, color_type, _, _, interlace = header
    assert color_type == 2 and interlace == 0, f"{path}: not a plain RGB PNG"
    bpp = 3 * depth // 8
    raw = zlib.decompress(idat)
    stride = width * bpp
    prev, out, p = bytearray(stride), [], 0
    for _ in range(height):
        kind, line = raw[p], bytearray(raw[p + 1:p + 1 + stride])
        p += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b, c = prev[x], (prev[x - bpp] if x >= bpp else 0)
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        prev = line
        if depth == 16:
            out.extend(struct.unpack(f">{stride // 2}H", bytes(line)))
        else:
            out.extend(line)
    return width, height, depth, out


def alive(pid):
    """The process exists and is not a zombie (killed, not yet reaped by its parent)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


def left_alive(pids, grace=2.0):
    """The pids still alive after `grace` seconds (a SIGKILLed grandchild dies when the
    kernel next schedules it, not at once)."""
    end = time.monotonic() + grace
    while any(alive(p) for p in pids) and time.monotonic() < end:
        time.sleep(0.01)
    return [p for p in pids if alive(p)]
