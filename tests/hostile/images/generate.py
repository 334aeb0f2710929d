#!/usr/bin/env python3
"""tests/hostile/images/generate.py — writes the hostile image files of tests/hostile/images/.

Each case is an image file (or a path such as /dev/zero) used as a texture or as the
environment, plus <case>.expect, the outcome tests/rt2/image/hostile_images_test.cpp checks
when it compiles a scene of that image (format in README.md). The files are written here,
byte by byte, because most lie in their headers (sizes, offsets, counts) in ways no image
writer would; they are committed, so the test needs no Python. Run it after changing a case.
"""
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
LIMIT = "is more than the limit of 268435456 (--max-texture-pixels raises it)"


def write(name, data):
    if isinstance(data, str):
        data = data.encode("ascii")
    assert len(data) < 50 * 1024, name
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data)


def case(name, use, path, error=None, ok=False, max_pixels=None):
    """use: "texture" or "environment"; path: the image, relative to this folder or absolute."""
    lines = [f"{use}: {path}"]
    lines.append("ok: true" if ok else f"error: {error}")
    if max_pixels is not None:
        lines.append(f"max_pixels: {max_pixels}")
    write(f"{name}.expect", "\n".join(lines) + "\n")


def both(name, file, data, error=None, ok=False):
    """`file` (written with `data`) as a texture (<name>_texture) and as an environment."""
    write(file, data)
    case(f"{name}_texture", "texture", file, error, ok)
    case(f"{name}_environment", "environment", file, error, ok)


# ---- PNG ------------------------------------------------------------------------------------

def png_chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def png(width, height, rows=None, depth=8, colour=2, interlace=0, compressed=None, crc=True):
    """A PNG of `rows` (bytes, filter byte included) or of the `compressed` IDAT bytes."""
    ihdr = struct.pack(">IIBBBBB", width, height, depth, colour, 0, 0, interlace)
    head = png_chunk(b"IHDR", ihdr)
    if not crc:
        head = head[:-4] + bytes(4)
    if compressed is None:
        compressed = zlib.compress(rows, 9)
    return (b"\x89PNG\r\n\x1a\n" + head + png_chunk(b"IDAT", compressed) +
            png_chunk(b"IEND", b""))


def rgb_rows(width, height):
    out = b""
    for y in range(height):
        out += b"\0" + bytes((x * 37 + y * 91 + c * 50) % 256 for x in range(width) for c in range(3))
    return out


def png_cases():
    # The example, shortened: a PNG declaring 20000 x 20000 whose stream holds 400
    # rows of zeros (the whole image would be a 1.2 MB file of 1.2 GB of pixels).
    rows = zlib.compressobj(9)
    body = b"".join(rows.compress(b"\0" * (1 + 3 * 20000)) for _ in range(400)) + rows.flush()
    both("png_declares_20000x20000", "png_declares_20000x20000.png", png(20000, 20000,
         compressed=body), f"20000 x 20000 pixels {LIMIT}")
    # Within the limit, 4096 x 4096, with only 1400 rows of data: a decompression bomb cut
    # short. Read as a texture (the cache reads it in tiles) until the data ends.
    rows = zlib.compressobj(9)
    body = b"".join(rows.compress(b"\0" * (1 + 3 * 4096)) for _ in range(1400)) + rows.flush()
    write("png_bomb_cut_short.png", png(4096, 4096, compressed=body))
    case("png_bomb_cut_short_texture", "texture", "png_bomb_cut_short.png",
         "cannot read texture")
    whole = png(32, 32, rgb_rows(32, 32))
    both("png_truncated", "png_truncated.png", whole[:len(whole) * 2 // 3], "cannot read")
    both("png_header_only", "png_header_only.png", whole[:33], "cannot read")
    both("png_bad_header_crc", "png_bad_header_crc.png", png(32, 32, rgb_rows(32, 32), crc=False),
         "cannot read image")
    both("png_zero_width", "png_zero_width.png", png(0, 32, b""), "cannot read image")
    both("png_width_2_31", "png_width_2_31.png", png(0x7FFFFFFF, 1, b"\0"), "")
    both("png_1x1", "png_1x1.png", png(1, 1, b"\0\x80\x40\x20"), ok=True)
    # 16 bits, grey and alpha; Adam7-interlaced (one pixel: pass 1 alone): valid, read
    rows = b"".join(b"\0" + bytes(range(4 * 7)) for _ in range(5))
    both("png_16bit_grey_alpha", "png_16bit_grey_alpha.png", png(7, 5, rows, depth=16, colour=4),
         ok=True)
    both("png_interlaced_1x1", "png_interlaced_1x1.png", png(1, 1, b"\0\x10\x20\x30",
         interlace=1), ok=True)
    # a texture limit of 31 x 32 pixels: a 32 x 32 image is refused, from its header
    write("png_32x32.png", whole)
    case("png_over_a_lower_limit", "texture", "png_32x32.png", f"32 x 32 pixels is more than "
         "the limit of 992 (--max-texture-pixels raises it)", max_pixels=992)
    case("png_at_a_lower_limit", "texture", "png_32x32.png", ok=True, max_pixels=1024)


# ---- JPEG -----------------------------------------------------------------------------------

# 16 x 16 RGB, baseline and progressive (oiiotool, with its metadata segments removed).
JPEG_BASELINE = bytes.fromhex(
    "ffd8ffe000104a46494600010100000100010000ffdb00430001010101010101010101010101010102010101"
    "0101020101010202020202020202020303040303030303020203040303040404040402030505040405040404"
    "04ffdb0043010101010101010201010204030203040404040404040404040404040404040404040404040404"
    "0404040404040404040404040404040404040404040404040404ffc000110800100010030122000211010311"
    "01ffc4001f0000010501010101010100000000000000000102030405060708090a0bffc400b5100002010303"
    "020403050504040000017d01020300041105122131410613516107227114328191a1082342b1c11552d1f024"
    "33627282090a161718191a25262728292a3435363738393a434445464748494a535455565758595a63646566"
    "6768696a737475767778797a838485868788898a92939495969798999aa2a3a4a5a6a7a8a9aab2b3b4b5b6b7"
    "b8b9bac2c3c4c5c6c7c8c9cad2d3d4d5d6d7d8d9dae1e2e3e4e5e6e7e8e9eaf1f2f3f4f5f6f7f8f9faffc400"
    "1f0100030101010101010101010000000000000102030405060708090a0bffc400b511000201020404030407"
    "05040400010277000102031104052131061241510761711322328108144291a1b1c109233352f0156272d10a"
    "162434e125f11718191a262728292a35363738393a434445464748494a535455565758595a63646566676869"
    "6a737475767778797a82838485868788898a92939495969798999aa2a3a4a5a6a7a8a9aab2b3b4b5b6b7b8b9"
    "bac2c3c4c5c6c7c8c9cad2d3d4d5d6d7d8d9dae2e3e4e5e6e7e8e9eaf2f3f4f5f6f7f8f9faffda000c030100"
    "02110311003f00f83ffe435ff4edf66ffb6dbf7fe58c6cfd68ff0090d7fd3b7d9bfedb6fdff9631b3f5a3fe4"
    "35ff004edf66ff00b6dbf7fe58c6cfd68ff90d7fd3b7d9bfedb6fdff009631b3f5afe88ff9377ff548ff00aa"
    "3ff757ff008871fdafff0081ff00adff00eb7f3ffd3fff0057fdbffcbaf65a7f587fc9cfff00aadbfd76ff00"
    "ba27fc453fec4ffc17fea47fa91ecffea1ff00d65fabff00cbdf6bafffd9")
JPEG_PROGRESSIVE = bytes.fromhex(
    "ffd8ffe000104a46494600010100000100010000ffdb00430001010101010101010101010101010102010101"
    "0101020101010202020202020202020303040303030303020203040303040404040402030505040405040404"
    "04ffdb0043010101010101010201010204030203040404040404040404040404040404040404040404040404"
    "0404040404040404040404040404040404040404040404040404ffc200110800100010030122000211010311"
    "01ffc4001500010100000000000000000000000000000007ffc4001401010000000000000000000000000000"
    "0007ffda000c030100021003100000018384458fffc4001510010100000000000000000000000000000033ff"
    "da0008010100010502b2cb2cffc4001f11000101090100000000000000000000001512001314163642636584"
    "92ffda0008010301013f01a9f766f8a6982f21022719277729bfffc4001f1100010109010000000000000000"
    "000000151200111416364262658491ffda0008010201013f01a775023ae5c8bf4b977e63d76a5bffc4001710"
    "0003010000000000000000000000000000125281ffda0008010100063f0295d257495d2574ffc40018100002"
    "0300000000000000000000000000001131f0f1ffda0008010100013f21b26f0b26f0b26f0b26f0ffda000c03"
    "01000200030000001003ffc400151101010000000000000000000000000000f0f1ffda0008010301013f1047"
    "74bfffc400151101010000000000000000000000000000f0f1ffda0008010201013f1007f37fffc400181000"
    "0203000000000000000000000000000011b1d1f0ffda0008010100013f10ce9a5333a694cce9a5333a694cff"
    "d9")


def jpeg_with_size(jpeg, width, height):
    """`jpeg` with its frame header (SOF0 or SOF2) declaring width x height."""
    b = bytearray(jpeg)
    for marker in (b"\xff\xc0", b"\xff\xc2"):
        i = b.find(marker)
        if i >= 0:
            b[i + 5:i + 9] = struct.pack(">HH", height, width)
    return bytes(b)


def jpeg_cases():
    both("jpeg_baseline", "jpeg_baseline.jpg", JPEG_BASELINE, ok=True)
    both("jpeg_progressive", "jpeg_progressive.jpg", JPEG_PROGRESSIVE, ok=True)
    both("jpeg_declares_60000x60000", "jpeg_declares_60000x60000.jpg",
         jpeg_with_size(JPEG_BASELINE, 60000, 60000), f"60000 x 60000 pixels {LIMIT}")
    # libjpeg's own limit (65500) refuses it first
    both("jpeg_declares_65535x65535", "jpeg_declares_65535x65535.jpg",
         jpeg_with_size(JPEG_BASELINE, 65535, 65535), "Maximum supported image dimension")
    both("jpeg_height_0", "jpeg_height_0.jpg", jpeg_with_size(JPEG_BASELINE, 16, 0), "")
    # 4096 x 4096, the progressive file's last scan repeated 1000 times: 1010 scans, each of
    # which libjpeg would decode over the whole image
    last = JPEG_PROGRESSIVE.rfind(b"\xff\xc4")
    scans = JPEG_PROGRESSIVE[:last] + JPEG_PROGRESSIVE[last:-2] * 1000 + b"\xff\xd9"
    both("jpeg_1010_scans", "jpeg_1010_scans.jpg", jpeg_with_size(scans, 4096, 4096),
         "a JPEG of more than 64 scans")
    both("jpeg_truncated", "jpeg_truncated.jpg", JPEG_BASELINE[:len(JPEG_BASELINE) - 200],
         "")
    both("jpeg_soi_only", "jpeg_soi_only.jpg", b"\xff\xd8\xff", "cannot read image")


# ---- OpenEXR --------------------------------------------------------------------------------

def exr_attribute(name, kind, value):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value


def exr(width, height, channels="BGR", x0=0, y0=0, extra=b"", deep=False, offsets=None,
        cut=None, piz=False, display=None):
    """A scanline OpenEXR of half channels, uncompressed with one line per chunk, or
    declaring PIZ compression (32 lines per chunk: a small offset table for a tall image)."""
    chlist = b"".join(c.encode() + b"\0" + struct.pack("<iBBBBii", 1, 0, 0, 0, 0, 1, 1)
                      for c in channels) + b"\0"
    box = struct.pack("<iiii", x0, y0, x0 + width - 1, y0 + height - 1)
    header = (exr_attribute("channels", "chlist", chlist) +
              exr_attribute("compression", "compression", b"\4" if piz else b"\0") +
              exr_attribute("dataWindow", "box2i", box) +
              exr_attribute("displayWindow", "box2i",
                            struct.pack("<iiii", 0, 0, display[0] - 1, display[1] - 1)
                            if display else box) +
              exr_attribute("lineOrder", "lineOrder", b"\0") +
              exr_attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0)) +
              exr_attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0)) +
              exr_attribute("screenWindowWidth", "float", struct.pack("<f", 1.0)) + extra)
    version = 2 | (0x800 if deep else 0)
    head = b"\x76\x2f\x31\x01" + struct.pack("<I", version) + header + b"\0"
    per_chunk = 32 if piz else 1
    declared = (height + per_chunk - 1) // per_chunk
    written = min(declared, 64)  # a lying header declares more chunks than the file has
    line = bytes(2 * width * len(channels)) if width * len(channels) < 4096 else b""
    start = len(head) + 8 * declared
    offsets_written, chunks = [], b""
    for i in range(written):
        offsets_written.append(offsets(i) if offsets else start + len(chunks))
        chunks += struct.pack("<ii", y0 + i * per_chunk, len(line)) + line
    listed = min(declared, cut // 8 + 1) if cut else declared  # a cut file: what remains
    table = b"".join(struct.pack("<Q", offsets_written[min(i, written - 1)])
                     for i in range(listed))
    data = head + table + chunks
    return data[:cut] if cut else data


def exr_cases():
    both("exr_3x2", "exr_3x2.exr", exr(3, 2), ok=True)
    both("exr_declares_20000x20000", "exr_declares_20000x20000.exr",
         exr(20000, 20000, piz=True), f"20000 x 20000 pixels {LIMIT}")
    # Offset tables longer than the file (OpenEXR reads them as it opens the file, and
    # stops at its end): 100000 lines, 2^30 lines (beyond OpenEXR's window limit), and a
    # ripmap of 1 x 1 tiles over 2^20 x 2^20 (beyond its tile limit)
    both("exr_declares_100000x100000", "exr_declares_100000x100000.exr",
         exr(100000, 100000, cut=2000), "Unexpected end of file")
    both("exr_declares_2_30_lines", "exr_declares_2_30_lines.exr", exr(4, 1 << 30, cut=2000),
         "Invalid display window")
    tiles = exr_attribute("tiles", "tiledesc", struct.pack("<IIB", 1, 1, 2))  # ripmap
    data = bytearray(exr(1 << 20, 1 << 20, extra=tiles, cut=3000))
    data[5] |= 0x02  # the version's "tiled" flag (0x200)
    both("exr_tiled_ripmap_of_2_20", "exr_tiled_ripmap_of_2_20.exr", bytes(data),
         "Maximum number of tiles exceeded")
    # Found by fuzzing: an attribute declaring 1.9 GB (OpenEXR allocated it, 7 s, then
    # found the end of the file)
    base = exr(2, 2)
    i = base.find(b"screenWindowWidth")  # and "float", 4 bytes, the value: 32 bytes
    data = base[:i] + b"screename\0string\0" + struct.pack("<I", 0x6F6C6600) + base[i + 32:]
    both("exr_attribute_of_1_9_gb", "exr_attribute_of_1_9_gb.exr", data,
         "attribute 'screename' declares 1869374976 bytes, more than the file holds")
    # Found by fuzzing: the same with a name of 41 characters, without the version's
    # long-names flag (OpenEXR reads names of up to 255 whatever the flag; rt2's screen
    # stopped at 31 and let the file through)
    data = base[:i] + b"x" * 41 + b"\0string\0" + struct.pack("<I", 1746953235) + base[i + 32:]
    both("exr_attribute_long_name_of_1_7_gb", "exr_attribute_long_name_of_1_7_gb.exr", data,
         "declares 1746953235 bytes, more than the file holds")
    # Found by fuzzing: OpenEXR reads a channel list to its end marker and most types'
    # fixed sizes, whatever the declared size says; a screen that skipped declared sizes
    # lost its place and missed the 1.9 GB attribute after a channel list declaring 0 bytes
    j = base.find(b"chlist\0") + 7
    data = base[:j] + struct.pack("<I", 0) + base[j + 4:i] + b"comments\0string\0" + \
        struct.pack("<I", 1869374976) + base[i + 32:]
    both("exr_channel_list_size_lies", "exr_channel_list_size_lies.exr", data,
         "attribute 'comments' declares 1869374976 bytes")
    # Found by fuzzing: rt2's message quoted the attribute's name, a line break
    data = base[:i] + b"\n\0\0" + struct.pack("<I", 16778241) + base[i + 32:]
    both("exr_attribute_named_line_break", "exr_attribute_named_line_break.exr", data,
         "attribute '?' declares 16778241 bytes")
    # OpenEXR refuses it first (its own limit on windows)
    both("exr_data_window_far", "exr_data_window_far.exr", exr(4, 4, x0=1 << 30, y0=-(1 << 30)),
         "Invalid display window")
    # Found by fuzzing: 3 x 2 pixels in a display window of 7077891 x 16777217, where OIIO's
    # texture cache makes its mip levels: its tile count overflowed and an assertion aborted
    both("exr_display_window_of_7077891x16777217", "exr_display_window_of_7077891x16777217.exr",
         exr(3, 2, display=(7077891, 16777217)),
         f"its display window of 7077891 x 16777217 pixels {LIMIT}")
    both("exr_data_window_off_origin", "exr_data_window_off_origin.exr",
         exr(4, 4, x0=600000000, y0=5), "is beyond 2^29 pixels from the origin")
    both("exr_1000_channels", "exr_1000_channels.exr", exr(2, 2, channels=[
         f"c{i:04d}" for i in range(1000)]), "1000 channels")
    both("exr_deep", "exr_deep.exr", exr(4, 4, deep=True, extra=exr_attribute(
         "type", "string", b"deepscanline")), "")
    both("exr_truncated", "exr_truncated.exr", exr(8, 8, cut=400), "cannot read")
    both("exr_offsets_beyond_the_file", "exr_offsets_beyond_the_file.exr",
         exr(8, 8, offsets=lambda y: 1 << 40), "cannot read")


# ---- Radiance HDR ---------------------------------------------------------------------------

def hdr(width, height, body):
    return (b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (height, width)) + body


def hdr_rle_line(width, pixel=(128, 64, 32, 129)):
    """One scanline in the new RLE form: each of the 4 components as runs of at most 127."""
    out = bytes([2, 2, width >> 8, width & 255])
    for c in pixel:
        left = width
        while left:
            n = min(left, 127)
            out += bytes([128 + n, c])
            left -= n
    return out


def hdr_cases():
    both("hdr_declares_20000x20000", "hdr_declares_20000x20000.hdr",
         hdr(20000, 20000, bytes(4 * 64)), f"20000 x 20000 pixels {LIMIT}")
    case("hdr_1x10000_environment", "environment", "hdr_1x10000.hdr", ok=True)
    write("hdr_1x10000.hdr", hdr(1, 10000, bytes([128, 64, 32, 129]) * 10000))
    both("hdr_10000x1", "hdr_10000x1.hdr", hdr(10000, 1, hdr_rle_line(10000)), ok=True)
    whole = hdr(64, 64, hdr_rle_line(64) * 64)
    both("hdr_truncated", "hdr_truncated.hdr", whole[:len(whole) // 2], "cannot read")
    # a run of 127 in a scanline of 64: past the scanline's end
    bad = bytes([2, 2, 0, 64]) + bytes([128 + 127, 1]) * 4
    both("hdr_run_past_the_line", "hdr_run_past_the_line.hdr", hdr(64, 2, bad * 2),
         "cannot read")
    both("hdr_negative_size", "hdr_negative_size.hdr", hdr(-5, 10, bytes(4)), "")
    both("hdr_no_size_line", "hdr_no_size_line.hdr", b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n",
         "cannot read image")


# ---- TIFF -----------------------------------------------------------------------------------

def tiff_ifd(entries, next_offset):
    """entries: (tag, type, count, value or offset) sorted by tag, little-endian."""
    out = struct.pack("<H", len(entries))
    for tag, kind, count, value in entries:
        if kind == 3 and count == 1:
            out += struct.pack("<HHIHH", tag, kind, count, value, 0)
        else:
            out += struct.pack("<HHII", tag, kind, count, value)
    return out + struct.pack("<I", next_offset)


def tiff(width, height, pages=1, strip_offset=None, loop=False, tile=0):
    """An 8-bit grey, uncompressed TIFF of `pages` pages, each one strip, or one tile of
    `tile` x `tile` (covering at most that much of the image)."""
    data = b"II*\0" + struct.pack("<I", 8)
    n = tile * tile if tile else min(width * height, 4096)  # a lying header declares more
    pixels = (bytes(range(256)) * (n // 256 + 1))[:n]
    ifd_size = 2 + 10 * 12 + 4
    for page in range(pages):
        ifd_at = len(data)
        strip_at = ifd_at + ifd_size
        last = page == pages - 1
        next_offset = ifd_at if loop else (0 if last else strip_at + len(pixels))
        entries = [(256, 4, 1, width), (257, 4, 1, height), (258, 3, 1, 8), (259, 3, 1, 1),
                   (262, 3, 1, 1), (273, 4, 1, strip_offset or strip_at), (277, 3, 1, 1),
                   (278, 4, 1, height), (279, 4, 1, min(width * height, 0xFFFFFFFF)),
                   (284, 3, 1, 1)]
        if tile:
            entries = entries[:5] + [(277, 3, 1, 1), (284, 3, 1, 1), (322, 3, 1, tile),
                                     (323, 3, 1, tile), (324, 4, 1, strip_at),
                                     (325, 4, 1, len(pixels))]
        data += tiff_ifd(entries, next_offset) + pixels
    return data


def tiff_cases():
    both("tiff_4x4", "tiff_4x4.tif", tiff(4, 4), ok=True)
    both("tiff_declares_100000x100000", "tiff_declares_100000x100000.tif",
         tiff(100000, 100000), f"100000 x 100000 pixels {LIMIT}")
    # OIIO's reader reports success, with black pixels and an error recorded
    both("tiff_strip_beyond_the_file", "tiff_strip_beyond_the_file.tif",
         tiff(16, 16, strip_offset=1 << 30), "Read error")
    both("tiff_100_pages", "tiff_100_pages.tif", tiff(2, 2, pages=100),
         "more than 64 subimages")
    # libtiff notices the loop: the first page is read
    both("tiff_directory_loop", "tiff_directory_loop.tif", tiff(2, 2, loop=True), ok=True)
    both("tiff_zero_width", "tiff_zero_width.tif", tiff(0, 4), "")
    # Found by fuzzing: OIIO 2.4's read_scanlines divides by zero on any tiled TIFF (rt2
    # used it to check a TIFF texture's reads; it reads whole tiles now)
    both("tiff_tiled_13x9", "tiff_tiled_13x9.tif", tiff(13, 9, tile=16), ok=True)


# ---- BMP, PNM, Targa, other files -----------------------------------------------------------

def bmp(width, height, pixels=b"", bpp=24, compression=0):
    info = struct.pack("<IiiHHIIiiII", 40, width, height, 1, bpp, compression, len(pixels), 2835,
                       2835, 0, 0)
    head = b"BM" + struct.pack("<IHHI", 14 + len(info) + len(pixels), 0, 0, 14 + len(info))
    return head + info + pixels


def tga(width, height, pixels=b""):
    return struct.pack("<BBBHHBHHHHBB", 0, 0, 2, 0, 0, 0, 0, 0, width, height, 24, 0x20) + pixels


def other_cases():
    both("bmp_2x2", "bmp_2x2.bmp", bmp(2, 2, bytes(range(16))), ok=True)
    # OIIO's BMP reader compares the size with the file's first
    both("bmp_declares_100000x100000", "bmp_declares_100000x100000.bmp",
         bmp(100000, -100000, bytes(64)), "Invalid image size 100000 x 100000")
    # Found by fuzzing: 24 bits per pixel and RLE4 compression crashed OIIO 2.4's reader
    both("bmp_rle4_24_bits", "bmp_rle4_24_bits.bmp", bmp(2, 2, b"\x02\x34\x00\x00\x00\x01",
         compression=2), "a run-length compressed BMP, which rt2 does not read")
    both("ppm_declares_100000x100000", "ppm_declares_100000x100000.ppm",
         b"P6\n100000 100000\n255\n" + bytes(64), f"100000 x 100000 pixels {LIMIT}")
    both("ppm_truncated", "ppm_truncated.ppm", b"P6\n16 16\n255\n" + bytes(100), "cannot read")
    both("pgm_maxval_0", "pgm_maxval_0.pgm", b"P5\n4 4\n0\n" + bytes(16), ok=True)
    both("tga_declares_65535x65535", "tga_declares_65535x65535.tga", tga(65535, 65535, bytes(64)),
         f"65535 x 65535 pixels {LIMIT}")
    both("tga_2x2", "tga_2x2.tga", tga(2, 2, bytes(range(12))), ok=True)
    gif = bytes.fromhex("474946383961010001008000000000ffffff2c00000000010001000002024401003b")
    both("gif_is_not_read", "gif_is_not_read.png", gif,
         "not a PNG, JPEG, OpenEXR, Radiance HDR, TIFF, BMP, PNM or Targa image")
    both("text_named_png", "text_named_png.png", "this is not an image\n", "cannot read image")
    both("empty", "empty.png", b"", "is empty")
    for use in ("texture", "environment"):
        case(f"directory_{use}", use, ".", "is a directory")
        case(f"dev_zero_{use}", use, "/dev/zero", "not a regular file")
        case(f"dev_null_{use}", use, "/dev/null", "not a regular file")
        case(f"proc_self_status_{use}", use, "/proc/self/status", "is empty")


def main():
    png_cases()
    jpeg_cases()
    exr_cases()
    hdr_cases()
    tiff_cases()
    other_cases()


if __name__ == "__main__":
    main()
