#!/usr/bin/env python3
"""Writes the procedural assets of the snake examples (issue 19), with the Python standard library only:

  examples/elaphe_skin.png      a corn snake's (Elaphe guttata) colour pattern in the procedural snake's body
                                coordinates: u from tail (0) to head (1), v = 1/2 + phi/2pi around the body
                                (the dorsal midline at v = 0.5, the belly at v = 0 and 1). Red saddles with
                                black borders along the back, smaller blotches on the flanks, an orange-tan
                                ground, a black-and-white chequered belly, a spear-point mark on the head.
  examples/xenopeltis_skin.png  a sunbeam snake (Xenopeltis unicolor): dark brown back, pale belly.
  examples/studio.hdr           a photographic studio as an equirectangular Radiance HDR (256 x 128, RLE):
                                a dark room, a large key softbox front-left, a fill strip on the right, a long
                                overhead strip behind the subject and a grey floor. Row 0 looks up (+y), the
                                centre column towards -z (docs/render.md).

Run from the repository root:

    python3 tools/make_snake_assets.py
"""
import math
import struct
import zlib


def srgb_encode(c):
    c = max(0.0, min(1.0, c))
    return 12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055


def write_png(path, w, h, pixel):
    """pixel(x, y) -> (r, g, b) in 0..255 (sRGB bytes)."""
    raw = bytearray()
    for y in range(h):
        raw.append(0)
        for x in range(w):
            raw.extend(pixel(x, y))

    def chunk(kind, data):
        c = struct.pack(">I", len(data)) + kind + data
        return c + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(bytes(raw), 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def smooth(e0, e1, x):
    t = max(0.0, min(1.0, (x - e0) / (e1 - e0)))
    return t * t * (3 - 2 * t)


def mix(a, b, t):
    return tuple(a[k] + (b[k] - a[k]) * t for k in range(3))


def noise(x, y, seed):
    """Smooth value noise in [0, 1] (a hash on the integer lattice, smoothstep-interpolated)."""

    def h(i, j):
        n = (i * 374761393 + j * 668265263 + seed * 2147483647) & 0xFFFFFFFF
        n = ((n ^ (n >> 13)) * 1274126177) & 0xFFFFFFFF
        return ((n ^ (n >> 16)) & 0xFFFF) / 65535.0

    i, j = math.floor(x), math.floor(y)
    fx, fy = x - i, y - j
    sx, sy = fx * fx * (3 - 2 * fx), fy * fy * (3 - 2 * fy)
    a = h(i, j) + (h(i + 1, j) - h(i, j)) * sx
    b = h(i, j + 1) + (h(i + 1, j + 1) - h(i, j + 1)) * sx
    return a + (b - a) * sy


def elaphe(u, v):
    """Linear RGB of the corn snake pattern at body coordinates (u, v). The body of the examples is ten
    units long and 0.9 across, so u is about 11 body widths and v one circumference."""
    ground = (0.30, 0.11, 0.040)  # orange-tan
    saddle = (0.28, 0.025, 0.012)  # red
    border = (0.018, 0.012, 0.010)  # black
    belly_white = (0.62, 0.58, 0.50)
    d = abs(v - 0.5)  # 0 on the dorsal midline, 0.5 on the ventral one
    # Belly: white with black blocks alternating left and right (the "Indian corn" chequer).
    if d > 0.36:
        k = u * 110.0
        side = 1 if v > 0.5 else 0
        chk = (int(math.floor(k)) + side) % 3 == 0 and abs(d - 0.43) < 0.045
        return border if chk else belly_white
    wobble = 0.25 * (noise(u * 60.0, v * 12.0, 3) - 0.5)
    c = ground
    # Dorsal saddles: 14 along the body, rounded blotches across the back, each with a black rim.
    n = 14.0
    x = (u * n) % 1.0 - 0.5
    r = ((abs(x) / 0.26) ** 2.5 + (d / 0.15) ** 2.5) ** 0.4 + wobble
    # Smaller lateral blotches, offset half a period, low on the flanks.
    xl = ((u * n + 0.5) % 1.0) - 0.5
    rl = ((abs(xl) / 0.13) ** 2.5 + (abs(d - 0.28) / 0.06) ** 2.5) ** 0.4 + wobble
    for rr in (r, rl):
        if rr < 1.2:
            c = mix(c, border, smooth(1.2, 1.05, rr))
        if rr < 1.0:
            c = mix(border, saddle, smooth(1.0, 0.85, rr))
    # Head: a spear point between the eyes on the plain ground.
    if u > 0.935:
        c = ground
        if abs((u - 0.965) / 0.022) + d / 0.09 < 1.0:
            c = saddle
    return c


def xenopeltis(u, v):
    d = abs(v - 0.5)
    back = (0.030, 0.022, 0.018)
    belly = (0.72, 0.70, 0.64)
    return mix(back, belly, smooth(0.34, 0.40, d))


def texture(path, w, h, f):
    def px(x, y):
        c = f((x + 0.5) / w, (y + 0.5) / h)
        return bytes(int(round(255 * srgb_encode(k))) for k in c)

    write_png(path, w, h, px)


# ---------------------------------------------------------------- the studio (Radiance HDR)


def direction(u, v):
    """docs/render.md: phi = (u - 1/2) 2pi, theta = v pi, d = (sin t sin p, cos t, -sin t cos p)."""
    phi = (u - 0.5) * 2 * math.pi
    th = v * math.pi
    return (math.sin(th) * math.sin(phi), math.cos(th), -math.sin(th) * math.cos(phi))


def softbox(d, centre_az, centre_el, half_w, half_h, radiance, edge=0.06):
    """A rectangle of constant radiance seen from the origin, with soft edges (angles in degrees)."""
    az = math.degrees(math.atan2(d[0], -d[2]))
    el = math.degrees(math.asin(max(-1.0, min(1.0, d[1]))))
    da = (az - centre_az + 180) % 360 - 180
    de = el - centre_el
    m = max(abs(da) / half_w, abs(de) / half_h)
    return tuple(c * smooth(1.0 + edge, 1.0 - edge, m) for c in radiance)


def studio(u, v):
    d = direction(u, v)
    if d[1] < -0.05:
        base = (0.05, 0.048, 0.045)  # grey floor, lit by the boxes
    else:
        t = max(0.0, d[1])
        base = mix((0.030, 0.030, 0.032), (0.010, 0.010, 0.012), t)  # dark walls and ceiling
    c = list(base)
    for box in (
        softbox(d, -40, 30, 22, 16, (9.0, 8.8, 8.4)),  # key: front left, above
        softbox(d, 70, 10, 8, 25, (3.0, 3.0, 3.1)),  # fill strip: right
        softbox(d, 180, 55, 35, 6, (6.0, 6.0, 6.2)),  # overhead strip behind the subject
    ):
        for k in range(3):
            c[k] += box[k]
    return c


def rgbe(c):
    m = max(c)
    if m < 1e-32:
        return (0, 0, 0, 0)
    e = math.frexp(m)[1]
    s = 256.0 / 2.0**e
    return (int(c[0] * s), int(c[1] * s), int(c[2] * s), e + 128)


def rle(channel):
    """Radiance's run-length encoding of one channel of one scanline."""
    out = bytearray()
    i, n = 0, len(channel)
    while i < n:
        run = 1
        while i + run < n and run < 127 and channel[i + run] == channel[i]:
            run += 1
        if run >= 4:
            out += bytes((128 + run, channel[i]))
            i += run
            continue
        j = i
        while j < n and j - i < 128:
            if j + 3 < n and channel[j] == channel[j + 1] == channel[j + 2] == channel[j + 3]:
                break
            j += 1
        out += bytes((j - i,)) + bytes(channel[i:j])
        i = j
    return out


def write_hdr(path, w, h, f):
    out = bytearray(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" + f"-Y {h} +X {w}\n".encode())
    for y in range(h):
        px = [rgbe(f((x + 0.5) / w, (y + 0.5) / h)) for x in range(w)]
        out += bytes((2, 2, w >> 8, w & 255))
        for k in range(4):
            out += rle([p[k] for p in px])
    with open(path, "wb") as fh:
        fh.write(out)


if __name__ == "__main__":
    texture("examples/elaphe_skin.png", 1024, 256, elaphe)
    texture("examples/xenopeltis_skin.png", 256, 64, xenopeltis)
    write_hdr("examples/studio.hdr", 256, 128, studio)
    print("wrote examples/elaphe_skin.png, examples/xenopeltis_skin.png, examples/studio.hdr")
