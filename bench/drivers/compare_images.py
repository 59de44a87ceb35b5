#!/usr/bin/env python3
"""Do two renders show the same objects in the same places?

    bench/drivers/compare_images.py HITRAY_MASK.ppm POV_MASK.ppm HITRAY.ppm POV.ppm PREVIEW.png

The masks are the flat id-colour renders bench/drivers/sdl2pov.py --mask sets up: every
object shows one colour of a 63-colour palette (4 levels per channel), the
background black. Each pixel is classified to the nearest palette colour
(after sRGB decoding of the 8-bit value, so either file's encoding works);
the script prints the share of pixels whose object ids agree, and writes a
preview PNG: the two shaded renders side by side, downscaled to 400 pixels
wide each, and below them the two masks, hitray's with the pixels where the
ids disagree in white. Only the Python standard library is used."""
import struct
import sys
import zlib


def read_ppm(path):
    with open(path, "rb") as f:
        data = f.read()
    fields, pos = [], 0
    while len(fields) < 4:  # magic, width, height, maxval; '#' comments between
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos) + 1
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    if fields[0] != b"P6" or int(fields[3]) != 255:
        raise SystemExit(f"compare_images: {path}: not an 8-bit binary PPM")
    width, height = int(fields[1]), int(fields[2])
    pixels = data[pos + 1:pos + 1 + 3 * width * height]
    if len(pixels) != 3 * width * height:
        raise SystemExit(f"compare_images: {path}: truncated")
    return width, height, pixels


def srgb_to_linear(v):
    c = v / 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


# Nearest of the levels 0, 1/3, 2/3, 1 for each 8-bit value, after decoding.
LEVEL = bytes(min(range(4), key=lambda k: abs(srgb_to_linear(v) - k / 3.0)) for v in range(256))


def ids(pixels):
    lv = pixels.translate(LEVEL)
    return bytes(lv[i] | lv[i + 1] << 2 | lv[i + 2] << 4 for i in range(0, len(lv), 3))


def downscale(width, height, pixels, out_width):
    step = max(1, -(-width // out_width))  # ceil: at most out_width wide
    rows = []
    for y in range(0, height - height % step, step):
        row = pixels[3 * y * width:3 * (y + 1) * width]
        rows.append(b"".join(row[3 * x:3 * x + 3] for x in range(0, width - width % step, step)))
    return len(rows[0]) // 3, rows


def write_png(path, width, rows):
    raw = b"".join(b"\x00" + r for r in rows)

    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body +
                struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))
    png = (b"\x89PNG\r\n\x1a\n" +
           chunk(b"IHDR", struct.pack(">IIBBBBB", width, len(rows), 8, 2, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(png)


def main():
    if len(sys.argv) != 6:
        raise SystemExit(__doc__)
    hm, pm, hs, ps, preview = sys.argv[1:]
    w, h, hmask = read_ppm(hm)
    w2, h2, pmask = read_ppm(pm)
    if (w, h) != (w2, h2):
        raise SystemExit("compare_images: the masks differ in size")
    a, b = ids(hmask), ids(pmask)
    same = sum(1 for x, y in zip(a, b) if x == y)
    print(f"{100.0 * same / len(a):.2f}")

    # Preview: shaded side by side, the disagreement map below.
    sw, srows_h = downscale(*read_ppm(hs), 400)
    _, srows_p = downscale(*read_ppm(ps), 400)
    marked = bytearray(hmask)
    for i, (x, y) in enumerate(zip(a, b)):
        if x != y:
            marked[3 * i:3 * i + 3] = b"\xff\xff\xff"
    mw, mrows = downscale(w, h, bytes(marked), 400)
    _, prows = downscale(w, h, pmask, 400)
    rows = [x + y for x, y in zip(srows_h, srows_p)]
    rows += [x + y + b"\x00" * 3 * (2 * sw - 2 * mw) for x, y in zip(mrows, prows)]
    write_png(preview, 2 * sw, rows)


if __name__ == "__main__":
    main()
