#!/usr/bin/env python3
"""tests/hostile/generate.py — writes the hostile loader inputs of tests/hostile/.

Each case is a scene or mesh (and the OBJ/MTL files it names, <case>.obj, <case>.mtl) plus
<case>.expect, the outcome tests/rt2/io/hostile_test.cpp checks (format in README.md). The cases
are made here rather than by hand because many are binary, huge or repetitive (UTF-16, NUL
bytes, 5000-deep nesting, 100 000 spheres, 1 MB lines); the files are committed, so the test
needs no Python. Run it from anywhere after changing a case: it rewrites every case file
(and removes none; delete a dropped case's files by hand).
"""
import gzip
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))

# Three lines, so that what follows starts at line 4.
CAMERA = "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 0, 0]\n"
# Lines 4-5: a material "red".
RED = "[materials.red]\ndiffuse = [1, 0, 0]\n"
TRIANGLE = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"


def sphere(radius="1", material='"red"', center="[0, 0, 0]"):
    return f"[[spheres]]\ncenter = {center}\nradius = {radius}\nmaterial = {material}\n"


def mesh(name, extra=""):
    return f'[[meshes]]\nfile = "{name}"\n{extra}'


def write(name, data):
    if isinstance(data, str):
        data = data.encode("utf-8")
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data)


def case(name, expect, **files):
    """files: ext=content ("toml", "obj", "mtl"); expect: the .expect lines."""
    for ext, content in files.items():
        write(f"{name}.{ext}", content)
    write(f"{name}.expect", expect.strip() + "\n")


def error(name, load_ext, message, line=None, file=None, **files):
    e = f"load: {name}.{load_ext}\nerror: {message}\n"
    if line is not None:
        e += f"line: {line}\n"
    if file is not None:
        e += f"file: {file}\n"
    case(name, e, **files)


def scene_error(name, toml, message, line=None, **files):
    error(name, "toml", message, line, toml=toml, **files)


def obj_error(name, obj, message, line=None, **files):
    """A bare OBJ (framed) whose loading fails."""
    error(name, "obj", message, line, obj=obj, **files)


def ok(name, load_ext, checks="", **files):
    case(name, f"load: {name}.{load_ext}\nok: true\n{checks}", **files)


# ---- malformed TOML -------------------------------------------------------------------------

def malformed_toml():
    scene_error("toml_unclosed_array", CAMERA + "fov = [50, 60\n", "invalid TOML", 4)
    scene_error("toml_missing_value", CAMERA + "fov =\n", "invalid TOML", 4)
    scene_error("toml_unclosed_header", "[camera\nposition = [0, 1, 5]\n", "invalid TOML", 1)
    scene_error("toml_key_without_value", CAMERA + "fov 50\n", "invalid TOML", 4)
    scene_error("toml_bad_escape", CAMERA + RED + sphere(material='"r\\qd"'), "invalid TOML", 9)
    scene_error("toml_bad_number", CAMERA + "fov = 5__0\n", "invalid TOML", 4)
    scene_error("toml_dangling_comma_inline",
                CAMERA + RED +
                "spheres = [{center = [0, 0, 0], radius = 1, material = \"red\",}]\n",
                "invalid TOML", 6)
    scene_error("toml_table_defined_twice", CAMERA + "[camera]\nfov = 50\n", "invalid TOML", 4)
    scene_error("toml_duplicate_key", CAMERA + "fov = 50\nfov = 60\n", "invalid TOML", 5)
    # toml++ 3.3 asserts on these table headers (found by fuzzing; see check_header_start).
    scene_error("toml_header_starts_with_comma", CAMERA + "[,materials.red]\n",
                "a table header must start with a key", 4)
    scene_error("toml_header_triple_bracket", CAMERA + "[[[a]]]\n",
                "a table header must start with a key", 4)
    scene_error("toml_header_then_newline", CAMERA + "[\n",
                "a table header must start with a key", 4)
    # toml++ 3.3 reaches TOML_UNREACHABLE on most non-ASCII characters where it expects
    # whitespace (found by fuzzing; see TomlScreen).
    scene_error("toml_non_ascii_after_number", CAMERA + "fov = 50\u02e2\n",
                "outside a string or comment", 4)
    scene_error("toml_non_ascii_bare_key", CAMERA + "caméra = 1\n",
                "outside a string or comment", 4)
    scene_error("toml_non_ascii_after_line_ending_backslash",
                CAMERA + RED + sphere(material='"""\\\n  \u00e9"""'),
                "valid TOML, but toml++ 3.3 cannot read it safely", 10)


def fuzz_found():
    """Inputs that crashed the fuzz targets (scripts/fuzz), minimised. All broke toml++ 3.3's
    own assertions (undefined behaviour in a release build); rt2 now refuses them before
    toml++ parses (TomlScreen in rt2/io/toml_scene.cpp). The first four are libFuzzer's
    -minimize_crash output (scripts/fuzz --target tomlpp --minimize); minimising the others
    that way ends at one of the first four, so they are minimised by hand."""
    scene_error("fuzz_header_bracket_equals", "[=", "a table header must start with a key", 1)
    scene_error("fuzz_header_bracket_newline", "[\n", "a table header must start with a key", 1)
    scene_error("fuzz_header_bracket_control", "[\x01", "a table header must start with a key", 1)
    scene_error("fuzz_non_ascii_alone", "\u02e2", "outside a string or comment", 1)
    scene_error("fuzz_close_brace_in_array", "x = [}", "'}' inside an array", 1)
    scene_error("fuzz_date_time_without_time", "x = 1979-05-27T:", "a date-time needs a time", 1)
    scene_error("fuzz_date_space_one_digit", "x = [1979-05-27 1]",
                "a value followed by a space and one digit", 1)
    scene_error("fuzz_date_like_space_one_digit", "x = [0, 1179-40-2[ 7, 1]",
                "a value followed by a space and one digit", 1)
    # tinyobjloader's tryParseDouble overflows an int on this exponent (found in an MTL).
    error("fuzz_mtl_exponent_overflow", "obj", "'0e-2147483648' has an exponent of 10 digits",
          2, file="fuzz_mtl_exponent_overflow.mtl",
          obj="mtllib fuzz_mtl_exponent_overflow.mtl\nusemtl red\n" + TRIANGLE,
          mtl="newmtl red\nKa 0.6 0.12 0e-2147483648\n")
    scene_error("fuzz_quotes_inside_a_number", "x = [ 0.\"\"\"m!\ufefa",
                "outside a string or comment", 1)
    scene_error("fuzz_quote_after_number", "x = 1'''\u00e9'''", "outside a string or comment", 1)


def review_found():
    """Inputs that got past the screen of fuzz_found(), found by reading the screen and
    toml++ 3.3 side by side (each crashed an asserting toml++), and an OBJ tag line that
    allocated megabytes."""
    # A comment or a CRLF line break between '[' and a value: the value is still screened.
    scene_error("review_comment_before_date_time", "x = [ # c\n1979-05-27T: ]\n",
                "a date-time needs a time", 2)
    scene_error("review_crlf_before_date_space_digit", "x = [\r\n1979-05-27 1]\r\n",
                "a value followed by a space and one digit", 2)
    scene_error("review_comment_before_quotes_in_number",
                'x = [ # c\n 0."""\u02e2""" ]\n', "outside a string or comment", 2)
    # A date, a space and a time are one token to toml++: no quote in it opens a string.
    scene_error("review_date_space_time_quotes", 'x = 1979-05-27 07:32:00."""\u02e2"""',
                "outside a string or comment", 1)
    scene_error("review_date_space_time_literal", "x = 1979-05-27 07:32:00Z.'\u02e2'",
                "outside a string or comment", 1)
    # Columns count characters, as toml++'s do, not bytes and not a byte-order mark.
    scene_error("review_column_after_bom", "\ufeffx = [}", ":1:6: invalid TOML: '}'", 1)
    scene_error("review_column_counts_characters", '"\u00e9\u00e9\u00e9" = [}',
                ":1:10: invalid TOML: '}'", 1)
    # tinyobjloader skips blanks after each '/' of a tag's counts: 16 384 values declared.
    obj_error("review_obj_tag_counts_after_blanks", TRIANGLE + "t a 0/ 8192/ 8192\n",
              "tag declares 16384 values, but the line has 0", 5)
    # A valid one passes the screen: toml++ parses it, and rt2 then names the unknown key.
    scene_error("review_date_space_time_valid",
                CAMERA + RED + "created = 1979-05-27 07:32:00Z\n" + sphere(),
                "unknown key 'created'", 6)


def truncated():
    glass = open(os.path.join(HERE, "..", "..", "scenes", "glass.toml"), encoding="utf-8").read()
    cut = glass.index("look_at") + len("look_at = [0, 0.")
    scene_error("truncated_toml_mid_number", glass[:cut], "invalid TOML")
    cut = glass.index('material = "') + len('material = "gl')
    scene_error("truncated_toml_mid_string", glass[:cut], "invalid TOML")
    cut = glass.index("[materials.") + len("[materi")
    scene_error("truncated_toml_mid_header", glass[:cut], "invalid TOML")
    obj = TRIANGLE + "v 1 1 0\nf 2 4 3\n"
    obj_error("truncated_obj_mid_face", obj[:-3], "face has 2 vertices; at least 3 are needed", 6)
    obj_error("truncated_obj_mid_vertex", "v 0 0 0\nv 1 0 0\nv 0 1",
              "vertex needs 3 coordinates", 3)
    obj_error("truncated_obj_mid_corner", TRIANGLE[:-2] + "/", "face corner '/' is not an index", 4)


# ---- encodings and garbage ----------------------------------------------------------------

def encodings():
    rng = random.Random(2)
    garbage = bytes(rng.randrange(256) for _ in range(4096))
    scene_error("binary_garbage", garbage, "NUL byte")
    no_nul = bytes(rng.randrange(1, 256) for _ in range(4096))
    scene_error("binary_garbage_without_nul", no_nul, "invalid TOML")
    obj_error("binary_garbage_obj", garbage, "")  # whatever the first bad line is: one line
    scene_error("empty", b"", "file is empty")
    obj_error("empty_obj", b"", "no faces")
    scene_error("only_comments_and_whitespace", "\n   \n# a comment\n\t\n# another\n\n",
                "missing required table [camera]")
    scene_text = CAMERA + RED + sphere()
    utf16 = scene_text.encode("utf-16-le")
    scene_error("utf16_le_with_bom", b"\xff\xfe" + utf16, "UTF-16")
    scene_error("utf16_be_with_bom", b"\xfe\xff" + scene_text.encode("utf-16-be"), "UTF-16")
    scene_error("utf16_le_without_bom", utf16, "NUL byte", 1)
    scene_error("invalid_utf8_in_string", (CAMERA + RED + sphere(material='"rXd"')).encode()
                .replace(b"X", b"\xc3\x28"), "invalid TOML", 9)
    scene_error("invalid_utf8_in_comment", CAMERA.encode() + b"# caf\xff\n", "invalid TOML", 4)
    scene_error("nul_in_string", (CAMERA + RED + sphere(material='"re\0d"')).encode(),
                "NUL byte", 9)
    # A UTF-8 byte-order mark is skipped, in TOML (toml++) and in OBJ and MTL (rt2).
    ok("utf8_bom", "toml", "quiet: true\nspheres: 1\n",
       toml=b"\xef\xbb\xbf" + (CAMERA + RED + sphere()).encode())
    ok("utf8_bom_obj", "obj", "quiet: true\nfaces: 1\nmaterial: utf8_bom_obj.obj:red\n",
       obj=b"\xef\xbb\xbfmtllib utf8_bom_obj.mtl\n" + ("usemtl red\n" + TRIANGLE).encode(),
       mtl=b"\xef\xbb\xbfnewmtl red\nKd 1 0 0\n")
    # An OBJ or MTL that is not text is refused at once, saying what it is.
    gz = gzip.compress(TRIANGLE.encode(), mtime=0)
    obj_error("obj_gzip", gz, "file is gzip-compressed; decompress it first")
    obj_error("obj_zip", b"PK\x03\x04\x14\x00\x00\x00\x08\x00" + gz[10:], "file is a ZIP archive")
    obj_error("obj_utf16_le_with_bom", b"\xff\xfe" + TRIANGLE.encode("utf-16-le"), "file is UTF-16")
    obj_error("obj_utf16_be_with_bom", b"\xfe\xff" + TRIANGLE.encode("utf-16-be"), "file is UTF-16")
    obj_error("obj_utf16_le_without_bom", TRIANGLE.encode("utf-16-le"),
              "file contains a NUL byte: it is binary or UTF-16", 1)
    error("mtl_gzip", "obj", "file is gzip-compressed", file="mtl_gzip.mtl",
          obj="mtllib mtl_gzip.mtl\nusemtl red\n" + TRIANGLE,
          mtl=gzip.compress(b"newmtl red\nKd 1 0 0\n", mtime=0))
    crlf = (CAMERA + RED + sphere() + mesh("crlf.obj")).replace("\n", "\r\n")
    ok("crlf", "toml", "quiet: true\nspheres: 1\nfaces: 2\nmaterial: crlf.obj:blue\n", toml=crlf,
       obj=("mtllib crlf.mtl\nusemtl blue\n" + TRIANGLE + "v 1 1 0\nf 2 4 3\n").replace(
           "\n", "\r\n"),
       mtl="newmtl blue\r\nKd 0 0 1\r\n")


# ---- depth --------------------------------------------------------------------------------

def depth():
    n = 5000
    scene_error("deep_arrays", CAMERA + "x = " + "[" * n + "]" * n + "\n", "nested", 4)
    scene_error("deep_inline_tables", CAMERA + "x = " + "{a = " * n + "1" + "}" * n + "\n",
                "nested", 4)
    scene_error("deep_arrays_of_inline_tables",
                CAMERA + "x = " + "[{a = " * n + "1" + "}]" * n + "\n",
                "nested", 4)
    scene_error("deep_dotted_keys", CAMERA + "a" + ".a" * n + " = 1\n", "nested", 4)
    scene_error("deep_table_header", CAMERA + "[a" + ".a" * n + "]\n", "nested", 4)
    scene_error("deep_quoted_dotted_keys", CAMERA + '"a"' + '."a"' * n + " = 1\n", "nested", 4)
    scene_error("deep_unclosed_arrays", CAMERA + "x = " + "[" * n + "\n", "", 4)


# ---- OBJ faces and vertices ---------------------------------------------------------------

def obj_faces():
    v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
    obj_error("obj_index_past_end", v3 + "f 1 2 4\n",
              "face references vertex 4, but only 3 vertices are defined", 4)
    obj_error("obj_index_huge", v3 + "f 1 2 2147483648\n", "face references vertex 2147483648", 4)
    obj_error("obj_index_overflows_64_bits", v3 + "f 1 2 99999999999999999999999\n",
              "is not an index", 4)
    obj_error("obj_index_zero", v3 + "f 0 1 2\n", "OBJ indices start at 1", 4)
    obj_error("obj_index_negative_too_far", v3 + "f -1 -2 -4\n", "(relative), but only 3", 4)
    obj_error("obj_index_most_negative", v3 + "f -1 -2 -9223372036854775808\n", "(relative)", 4)
    obj_error("obj_normal_index_past_end", v3 + "vn 0 0 1\nf 1//1 2//1 3//2\n",
              "face references normal 2, but only 1 normal is defined", 5)
    obj_error("obj_texcoord_index_zero", v3 + "vt 0 0\nf 1/0 2/1 3/1\n",
              "face references texture coordinate 0", 5)
    obj_error("obj_corner_four_parts", v3 + "vt 0 0\nvn 0 0 1\nf 1/1/1/1 2 3\n",
              "has more than 3 parts", 6)
    obj_error("obj_line_only_f", v3 + "f\n", "face has 0 vertices", 4)
    obj_error("obj_line_only_v", v3 + "v\nf 1 2 3\n", "vertex needs 3 coordinates, got 0", 4)
    obj_error("obj_vertex_nan", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "vertex is not finite", 1)
    obj_error("obj_vertex_inf", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n", "vertex is not finite", 2)
    obj_error("obj_vertex_1e39", "v 0 0 0\nv 1 0 0\nv 0 1e39 0\nf 1 2 3\n",
              "vertex is not finite", 3)
    obj_error("obj_vertex_minus_1e39", "v 0 0 -1e39\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
              "vertex is not finite", 1)
    obj_error("obj_vertex_exponent_overflow", "v 0 0 0e2147483648\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
              "has an exponent of 10 digits", 1)
    obj_error("obj_normal_exponent_overflow", v3 + "vn 0 0 1e-2147483649\nf 1//1 2//1 3//1\n",
              "has an exponent of 10 digits", 4)
    # Tags (t name ints/reals/strings ...) must hold the values they declare: tinyobjloader
    # allocates them all, up to 8192 of each per line.
    obj_error("obj_tag_declares_too_many_values", TRIANGLE + "t crease 8192/8192/8192\n",
              "tag declares 24576 values, but the line has 0", 5)
    obj_error("obj_tag_counts_read_as_atoi", TRIANGLE + "t crease 2x/1y/0 1\n",
              "tag declares 3 values, but the line has 1", 5)
    ok("obj_tag_with_its_values", "obj", "quiet: true\nfaces: 1\n",
       obj=TRIANGLE + "t crease 2/1/0 1 2 0.5\n")
    obj_error("obj_vertex_not_a_number", "v 0 0 zero\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
              "'zero' is not a number", 1)
    # Degenerate faces are dropped and counted; when none is left the mesh is an error.
    obj_error("obj_only_degenerate_faces", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n",
              "all 2 faces are degenerate")
    obj_error("obj_no_faces", v3 + "vn 0 0 1\n# no f lines\n", "no faces")
    ok("obj_one_face", "obj", "quiet: true\nfaces: 1\n", obj=TRIANGLE)
    ok("obj_some_degenerate_faces", "obj", "quiet: true\nfaces: 1\ndegenerate: 1\n",
       obj=TRIANGLE + "f 1 1 2\n")
    # Convex polygons of 4..100 vertices (fans are triangulated: n - 2 triangles each).
    lines, faces, total = [], [], 0
    for n in (4, 5, 6, 7, 8, 16, 31, 64, 100):
        base = total
        for k in range(n):
            a = 2 * math.pi * k / n
            lines.append(f"v {math.cos(a):.6f} {math.sin(a):.6f} {len(faces)}")
        faces.append("f " + " ".join(str(base + k + 1) for k in range(n)))
        total += n
    ok("obj_polygons_4_to_100", "obj",
       f"quiet: true\nfaces: {sum(n - 2 for n in (4, 5, 6, 7, 8, 16, 31, 64, 100))}\n",
       obj="\n".join(lines + faces) + "\n")
    # Polygons as modellers write them (tinyobjloader filled the ring's hole, fanned the frame
    # across its hole, split the dart outside itself, and read 300 corners as 44).
    ring = [f"v {r * math.cos(2 * math.pi * k / 32):.6f} {r * math.sin(2 * math.pi * k / 32):.6f} 0"
            for r in (1.0, 0.93) for k in range(32)]
    corners = list(range(1, 33)) + [1, 33] + list(range(64, 33, -1)) + [33]
    ok("obj_polygon_lightwave_ring", "obj", "quiet: true\nfaces: 64\ndegenerate: 0\n",
       obj="# a ring as LightWave writes it: a bridge edge from vertex 1 to 33, walked twice\n" +
       "\n".join(ring) + "\nf " + " ".join(map(str, corners)) + "\n")
    ok("obj_polygon_square_frame", "obj", "quiet: true\nfaces: 8\ndegenerate: 0\n",
       obj="v 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\nv 1 1 0\nv 1 3 0\nv 3 3 0\nv 3 1 0\n"
       "f 1 2 3 4 1 5 6 7 8 5\n")
    ok("obj_polygon_concave_quad", "obj", "quiet: true\nfaces: 2\ndegenerate: 0\n",
       obj="v 0 0 0\nv 1 0.2 0\nv 2 0 0\nv 1 3 0\nf 1 2 3 4\n")
    circle = [f"v {math.cos(2 * math.pi * k / 300):.6f} {math.sin(2 * math.pi * k / 300):.6f} 0"
              for k in range(300)]
    ok("obj_polygon_300_corners", "obj", "quiet: true\nfaces: 298\ndegenerate: 0\n",
       obj="\n".join(circle) + "\nf " + " ".join(str(k + 1) for k in range(300)) + "\n")
    # A figure eight through a repeated corner has no net area, hence no plane: the polygon
    # is fanned (two triangles, two degenerate), with a warning.
    ok("obj_polygon_figure_eight", "obj",
       "warning: obj_polygon_figure_eight.obj:6: a polygon of 6 corners intersects itself or is "
       "degenerate\nfaces: 2\ndegenerate: 2\n",
       obj="v 0 0 0\nv 1 -1 0\nv 1 1 0\nv -1 -1 0\nv -1 1 0\nf 1 2 3 1 4 5\n")
    # Coordinates a float area cannot hold: named, not "degenerate" alone.
    obj_error("obj_coordinates_1e37", "v 0 0 0\nv 1e37 0 0\nv 0 1e37 0\nf 1 2 3\n",
              "the coordinates are too large for float arithmetic")
    obj_error("obj_coordinates_1e-30", "v 0 0 0\nv 1e-30 0 0\nv 0 1e-30 0\nf 1 2 3\n",
              "the coordinates are too small for float arithmetic")


# ---- TOML numbers: NaN, inf and absurd values ----------------------------------------------

def numbers():
    tri_scene = lambda name, extra: CAMERA + mesh(f"{name}.obj", extra)  # noqa: E731
    for name, toml, line in [
        ("nan_camera_position", "[camera]\nposition = [nan, 1, 5]\nlook_at = [0, 0, 0]\n", 2),
        ("inf_camera_look_at", "[camera]\nposition = [0, 1, 5]\nlook_at = [0, +inf, 0]\n", 3),
        ("nan_camera_up", CAMERA + "up = [0, -nan, 0]\n", 4),
        ("inf_fov", CAMERA + "fov = inf\n", 4),
        ("nan_radius", CAMERA + RED + sphere(radius="nan"), 8),
        ("neg_inf_sphere_center", CAMERA + RED + sphere(center="[0, -inf, 0]"), 7),
        ("inf_diffuse", CAMERA + "[materials.red]\ndiffuse = [1, inf, 0]\n", 5),
        ("nan_shininess", CAMERA + "[materials.red]\nshininess = nan\n", 5),
        ("nan_world_ambient", CAMERA + "[world]\nambient = [nan, 0, 0]\n", 5),
        ("nan_light_intensity", CAMERA + "[[lights]]\nposition = [0, 5, 0]\nintensity = nan\n", 6),
        ("inf_light_color", CAMERA + "[[lights]]\nposition = [0, 5, 0]\ncolor = [inf, 1, 1]\n", 6),
        ("nan_plane_offset",
         CAMERA + RED + "[[planes]]\nnormal = [0, 1, 0]\noffset = nan\nmaterial = \"red\"\n", 8),
    ]:
        scene_error(name, toml, "must be a finite number", line)
    for name, extra, line in [("inf_scale", "scale = -inf\n", 6),
                              ("nan_rotate", "rotate = [0, +nan, 0]\n", 6),
                              ("inf_translate", "translate = [inf, 0, 0]\n", 6)]:
        scene_error(name, tri_scene(name, extra), "must be a finite number", line, obj=TRIANGLE)
    for name, toml, message, line in [
        ("radius_1e-300", CAMERA + RED + sphere(radius="1e-300"), "radius must be > 0", 8),
        ("radius_negative", CAMERA + RED + sphere(radius="-1"), "radius must be > 0", 8),
        ("radius_1e300", CAMERA + RED + sphere(radius="1e300"), "too large", 8),
        ("radius_integer_overflow", CAMERA + RED + sphere(radius="9223372036854775808"),
         "invalid TOML", 8),
        ("fov_0", CAMERA + "fov = 0\n", "camera.fov must be in (0, 180)", 4),
        ("fov_180", CAMERA + "fov = 180\n", "camera.fov must be in (0, 180)", 4),
        ("fov_1000", CAMERA + "fov = 1000\n", "camera.fov must be in (0, 180)", 4),
        ("ior_0", CAMERA + "[materials.glass]\nior = 0\n", "ior must be in (0, 100]", 5),
        ("ior_1000", CAMERA + "[materials.glass]\nior = 1000\n", "ior must be in (0, 100]", 5),
        ("shininess_negative", CAMERA + "[materials.m]\nshininess = -1\n", "must be >= 0", 5),
        ("intensity_negative", CAMERA + "[[lights]]\nposition = [0, 5, 0]\nintensity = -1\n",
         "intensity must be >= 0", 6),
        ("transparency_2", CAMERA + "[materials.m]\ntransparency = 2\n", "must be in [0, 1]", 5),
        ("colour_negative", CAMERA + "[materials.m]\nspecular = [0, -0.5, 0]\n", "must be >= 0", 5),
        ("light_range_0", CAMERA + "[[lights]]\nposition = [0, 5, 0]\nrange = 0\n",
         "lights[0].range must be > 0", 6),
        ("light_range_inf", CAMERA + "[[lights]]\nposition = [0, 5, 0]\nrange = inf\n",
         "must be a finite number", 6),
        ("light_field_count_negative",
         CAMERA + "[light_field]\ncount = -1\nmin = [0, 0, 0]\nmax = [1, 1, 1]\nrange = 1\n",
         "light_field.count must be in [0, 1000000]", 5),
        ("light_field_count_huge",
         CAMERA + "[light_field]\ncount = 1000001\nmin = [0, 0, 0]\nmax = [1, 1, 1]\nrange = 1\n",
         "light_field.count must be in [0, 1000000]", 5),
        ("light_field_count_float",
         CAMERA + "[light_field]\ncount = 2.5\nmin = [0, 0, 0]\nmax = [1, 1, 1]\nrange = 1\n",
         "light_field.count must be an integer", 5),
        ("light_field_box_inverted",
         CAMERA + "[light_field]\ncount = 2\nmin = [0, 0, 0]\nmax = [1, -1, 1]\nrange = 1\n",
         "light_field.max must be >= min", 7),
        ("light_field_range_pair_inverted",
         CAMERA + "[light_field]\ncount = 2\nmin = [0, 0, 0]\nmax = [1, 1, 1]\nrange = [2, 1]\n",
         "light_field.range must have lo <= hi", 8),
        ("light_field_range_three",
         CAMERA + "[light_field]\ncount = 2\nmin = [0, 0, 0]\nmax = [1, 1, 1]\nrange = [1, 2, 3]\n",
         "light_field.range must be a number or an array of 2 numbers", 8),
        ("light_field_range_missing",
         CAMERA + "[light_field]\ncount = 2\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n",
         "missing the required key 'range'", 4),
        ("light_field_unknown_key",
         CAMERA + "[light_field]\ncount = 2\nmin = [0, 0, 0]\nmax = [1, 1, 1]\nrange = 1\nradius = 1\n",
         "unknown key 'radius' in light_field", 9),
        ("light_field_not_a_table", "light_field = 3\n" + CAMERA, "light_field must be a table", 1),
    ]:
        scene_error(name, toml, message, line)
    scene_error("scale_zero", tri_scene("scale_zero", "scale = 0\n"), "must not be zero", 6,
                obj=TRIANGLE)
    scene_error("scale_1e30", tri_scene("scale_1e30", "scale = 1e30\n"), "too large", 6,
                obj=TRIANGLE)
    scene_error("scale_flattens_mesh", tri_scene("scale_flattens_mesh", "scale = 1e-30\n"),
                "degenerate after the transform", 4, obj=TRIANGLE)
    # Areas that overflow a float count as degenerate (vertices cannot: 1e19 * 1e15 < 3e38).
    scene_error("scale_overflows_area", tri_scene("scale_overflows_area", "scale = 1e15\n"),
                "is degenerate after the transform", 4,
                obj="v 0 0 0\nv 1e9 0 0\nv 0 1e9 0\nf 1 2 3\n")


# ---- keys and types -----------------------------------------------------------------------

def keys():
    for name, toml, message, line in [
        ("missing_camera", RED + sphere(), "missing required table [camera]", None),
        ("missing_camera_position", "[camera]\nlook_at = [0, 0, 0]\n",
         "camera is missing the required key 'position'", 1),
        ("missing_radius", CAMERA + RED + "[[spheres]]\ncenter = [0, 0, 0]\nmaterial = \"red\"\n",
         "spheres[0] is missing the required key 'radius'", 6),
        ("missing_mesh_file", CAMERA + "[[meshes]]\nscale = 2\n",
         "meshes[0] is missing the required key 'file'", 4),
        ("wrong_type_radius", CAMERA + RED + sphere(radius='"big"'),
         "spheres[0].radius must be a number (got a string)", 8),
        ("wrong_type_vector_length", CAMERA + "up = [0, 1]\n", "got 2 elements", 4),
        ("wrong_type_vector_element", CAMERA + "up = [0, true, 0]\n",
         "camera.up[1] must be a number (got a boolean)", 4),
        ("wrong_type_spheres_table", CAMERA + RED + "[spheres]\nradius = 1\n",
         "spheres must be an array of tables", 6),
        ("wrong_type_camera", "camera = 5\n", "camera must be a table (got an integer)", 1),
        ("wrong_type_material_name", CAMERA + RED + sphere(material="3"),
         "material must be a string (got an integer)", 9),
        ("wrong_type_date", CAMERA + "fov = 1979-05-27\n", "must be a number (got a date)", 4),
        ("unknown_key_with_hint", CAMERA + RED + "[[spheres]]\ncenter = [0, 0, 0]\nradious = 1\n"
         "material = \"red\"\n", "unknown key 'radious' in spheres[0] (did you mean 'radius'?)", 8),
        ("unknown_top_level_table", CAMERA + "[camrea]\nfov = 50\n",
         "unknown key 'camrea' (did you mean 'camera'?)", 4),
        ("undefined_material", CAMERA + RED + sphere(material='"rde"'),
         "undefined material 'rde' (did you mean 'red'?)", 9),
        ("look_at_equals_position", "[camera]\nposition = [1, 1, 1]\nlook_at = [1, 1, 1]\n",
         "look_at must differ from camera.position", 3),
        ("empty_material_name", CAMERA + RED + sphere(material='""'), "must not be empty", 9),
    ]:
        scene_error(name, toml, message, line)
    # Unicode and spaces in a TOML material name are fine (the key is quoted).
    ok("material_name_unicode_and_spaces", "toml",
       "quiet: true\nmaterial: rouge vif écarlate ✓\n",
       toml=CAMERA + '[materials."rouge vif écarlate ✓"]\ndiffuse = [1, 0, 0]\n' +
       sphere(material='"rouge vif écarlate ✓"'))


# ---- files and paths ----------------------------------------------------------------------

def paths():
    scene_error("mesh_file_missing", CAMERA + mesh("models/nothing-here.obj"),
                "nothing-here.obj': file not found", 5)
    scene_error("mesh_file_is_a_directory", CAMERA + mesh("."), "is a directory, not a file", 5)
    scene_error("mesh_file_is_dev_zero", CAMERA + mesh("/dev/zero"), "is not a regular file", 5)
    scene_error("mesh_file_is_dev_urandom", CAMERA + mesh("/dev/urandom"),
                "is not a regular file", 5)
    # /proc files are "regular" but report a size of 0 and never end (pagemap is terabytes).
    scene_error("mesh_file_is_proc_pagemap", CAMERA + mesh("/proc/self/pagemap"),
                "not an ordinary file", 5)
    # The scene names itself as its mesh: TOML lines are not OBJ statements, so no faces.
    error("mesh_file_is_the_scene", "toml", "no faces", file="mesh_file_is_the_scene.toml",
          toml=CAMERA + mesh("mesh_file_is_the_scene.toml"))
    error("unknown_extension", "txt", "unknown file extension '.txt'", txt=CAMERA)
    # MTL libraries: missing (a warning), the OBJ itself, named twice and naming itself.
    ok("mtl_missing", "obj",
       "warning: material library 'nowhere.mtl' not found; using the default material\n"
       "faces: 1\nmaterial: default\n",
       obj="mtllib nowhere.mtl\nusemtl red\n" + TRIANGLE)
    ok("mtl_is_the_obj", "obj",
       "warning: material 'red' is not in the material libraries\nfaces: 1\n",
       obj="mtllib mtl_is_the_obj.obj\nusemtl red\n" + TRIANGLE)
    ok("mtllib_chain_to_itself", "obj", "quiet: true\nfaces: 1\nmaterial: "
       "mtllib_chain_to_itself.obj:red\n",
       obj="mtllib mtllib_chain_to_itself.mtl mtllib_chain_to_itself.mtl\n"
       "mtllib mtllib_chain_to_itself.mtl\nusemtl red\n" + TRIANGLE,
       mtl="mtllib mtllib_chain_to_itself.mtl\nnewmtl red\nKd 1 0 0\n")
    ok("mtl_is_a_directory", "obj",
       "warning: material library '.' is not a regular file\nfaces: 1\n",
       obj="mtllib .\n" + TRIANGLE)
    ok("mtl_is_dev_zero", "obj",
       "warning: material library '/dev/zero' is not a regular file\nfaces: 1\n",
       obj="mtllib /dev/zero\n" + TRIANGLE)
    ok("usemtl_undefined", "obj",
       "warning: usemtl_undefined.obj:2: material 'ghost' is not in the material libraries\n"
       "faces: 2\nmaterial: usemtl_undefined.obj:red\nmaterial: default\n",
       obj="mtllib usemtl_undefined.mtl\nusemtl ghost\n" + TRIANGLE + "usemtl red\nf 1 3 2\n",
       mtl="newmtl red\nKd 1 0 0\n")
    # `newmtl  red` (two blanks) is the material "red" that `usemtl red` uses, with no warning.
    ok("newmtl_two_blanks", "obj", "quiet: true\nfaces: 1\nmaterial: newmtl_two_blanks.obj:red\n",
       obj="mtllib newmtl_two_blanks.mtl\nusemtl red\n" + TRIANGLE,
       mtl="newmtl  red\nKd 1 0 0\nnewmtl \t blue  \nKd 0 0 1\n")
    ok("mtl_name_unicode", "obj", "quiet: true\nmaterial: mtl_name_unicode.obj:écarlate✓\n",
       obj="mtllib mtl_name_unicode.mtl\nusemtl écarlate✓\n" + TRIANGLE,
       mtl="newmtl écarlate✓\nKd 1 0 0\n")
    # An MTL name with a space: usemtl takes the rest of the line, as newmtl does (it read one
    # word, as tinyobjloader does, and "my red" was not found as "my").
    ok("mtl_name_with_space", "obj",
       "quiet: true\nmaterial: mtl_name_with_space.obj:my red\n",
       obj="mtllib mtl_name_with_space.mtl\nusemtl my red\n" + TRIANGLE,
       mtl="newmtl my red\nKd 1 0 0\n")
    ok("usemtl_name_with_spaces_and_tabs", "obj",
       "quiet: true\ndiffuse: 0.6 0.4 0.2 usemtl_name_with_spaces_and_tabs.obj:Hard Wood\n",
       obj="mtllib usemtl_name_with_spaces_and_tabs.mtl\nusemtl \t Hard Wood \t\n" + TRIANGLE,
       mtl="newmtl Hard Wood\nKd 0.6 0.4 0.2\n")


# ---- MTL values -----------------------------------------------------------------------------

def mtl_values():
    """Every MTL number is checked as an OBJ vertex is (tinyobjloader read a bad one as 0, and
    `Kd 0.5` as dark red)."""
    def mtl_case(name, mtl, expect):
        case(name, f"load: {name}.obj\n{expect}",
             obj=f"mtllib {name}.mtl\nusemtl m\n" + TRIANGLE, mtl="newmtl m\n" + mtl)

    def mtl_error(name, mtl, message, line):
        mtl_case(name, mtl, f"error: {message}\nline: {line}\nfile: {name}.mtl\n")

    mtl_case("mtl_one_number_is_grey", "Ka 0.1\nKd 0.5\nKs 0.25\nNs 10\n",
             "ok: true\nquiet: true\ndiffuse: 0.5 0.5 0.5 mtl_one_number_is_grey.obj:m\n"
             "specular: 0.25 0.25 0.25 mtl_one_number_is_grey.obj:m\n")
    mtl_error("mtl_ns_nan", "Kd 1 1 1\nNs nan\n", "Ns must be a finite number (got 'nan')", 3)
    mtl_error("mtl_kd_nan", "Kd nan\n", "Kd must be a finite number (got 'nan')", 2)
    mtl_error("mtl_kd_words", "Kd red green blue\n", "Kd must be a number (got 'red')", 2)
    mtl_error("mtl_kd_two_numbers", "Kd 0.5 0.5\n", "Kd needs 1 or 3 numbers (got 2)", 2)
    mtl_error("mtl_ks_1e39", "Ks 1 1e39 1\n", "Ks must be a finite number (got '1e39')", 2)
    mtl_error("mtl_ni_inf", "Ni inf\n", "Ni must be a finite number (got 'inf')", 2)
    mtl_error("mtl_d_word", "d opaque\n", "d must be a number (got 'opaque')", 2)
    mtl_error("mtl_illum_word", "illum two\n", "illum must be an integer from 0 to 10", 2)
    # 3ds Max writes Ns 0 with Ks > 0 for matte surfaces: exponent 0 is no highlight (a
    # highlight of exponent 0 covers the whole lit side in Ks).
    mtl_case("mtl_ns_0_with_ks", "Kd 0.5\nKs 0.9\nNs 0\n",
             "ok: true\nquiet: true\nspecular: 0 0 0 mtl_ns_0_with_ks.obj:m\n")
    # Unsupported texture statements: one warning per MTL file, however many there are; a
    # texture file that is missing: a warning, and the material keeps its colour.
    mtl_case("mtl_textures", "Kd 0.5\nmap_Kd wood.png\nmap_bump -bm 2 bump.png\nbump b.png\n",
             "ok: true\nwarning: mtl_textures.mtl:4: 'map_bump' is not supported\n"
             "warning: texture 'wood.png' not found; ignored\n"
             "diffuse: 0.5 0.5 0.5 mtl_textures.obj:m\n")


# ---- size ---------------------------------------------------------------------------------

def sizes():
    # These inputs are megabytes: the files are not committed. tests/rt2/io/hostile_test.cpp
    # writes them (same contents as described here) into a temporary folder when a case
    # loads "generated/<file>"; see make_generated() there.
    #   spheres_100000.toml:         CAMERA, material m, 100 000 spheres of radius 0.4
    #   long_line_toml_comment.toml: CAMERA + RED, a 1 MiB comment, one sphere
    #   long_line_obj_comment.obj:   a 1 MiB comment, then TRIANGLE
    #   long_line_obj_vertex.obj:    "v 0 0 0" + 262 144 more coordinates, a triangle
    #   long_line_toml_key.toml:     CAMERA, then a 1 MiB key on line 4
    #   obj_polygon_100000_corners.obj: a circle of 100 000 corners, one face (tinyobjloader
    #                                   took 21-50 s, and lost triangles)
    #   obj_polygon_random_20000.obj:   one face through 20 000 random points (self-intersecting)
    #   mtl_1000000_materials.obj/.mtl: a triangle using material m999999 of a million
    #                                   (tinyobjloader held 2.3 GB)
    #   obj_zeros_2_gib.obj:            2 GiB of zero bytes, a sparse file (refused after 64 KiB)
    def generated(name, ext, expect):
        write(f"{name}.expect", f"load: generated/{name}.{ext}\n{expect}")
    generated("spheres_100000", "toml", "ok: true\nquiet: true\nspheres: 100000\n")
    generated("long_line_toml_comment", "toml", "ok: true\nquiet: true\nspheres: 1\n")
    generated("long_line_obj_comment", "obj", "ok: true\nquiet: true\nfaces: 1\n")
    generated("long_line_obj_vertex", "obj", "ok: true\nquiet: true\nfaces: 1\n")
    generated("long_line_toml_key", "toml", "error: unknown key\nline: 4\n")
    generated("obj_polygon_100000_corners", "obj", "ok: true\nquiet: true\nfaces: 99998\n")
    generated("obj_polygon_random_20000", "obj",
              "ok: true\nwarning: a polygon of 20000 corners intersects itself or is degenerate\n")
    generated("mtl_1000000_materials", "obj",
              "ok: true\nquiet: true\nfaces: 1\n"
              "diffuse: 0.5 0.5 0.5 mtl_1000000_materials.obj:m999999\n")
    generated("obj_zeros_2_gib", "obj", "error: file contains a NUL byte\nline: 1\n")


# ---- glTF 2.0 ---------------------------------------------------------------------------------

def gltf_json(extra=None, positions=(0, 0, 0, 1, 0, 0, 0, 1, 0), indices=None, glb=False,
              views=None, accessors=None, primitive=None, nodes=None):
    """A glTF of one triangle: its buffer holds `positions` (floats) and `indices` (unsigned
    int); `extra` replaces or adds top-level members; views/accessors/primitive/nodes replace
    the defaults. Returns (json_dict, bin_bytes)."""
    import struct
    bin_ = struct.pack(f"<{len(positions)}f", *positions)
    pos_len = len(bin_)
    if indices is not None:
        bin_ += struct.pack(f"<{len(indices)}I", *indices)
    d = {"asset": {"version": "2.0"},
         "buffers": [{"byteLength": len(bin_)}],
         "bufferViews": views if views is not None else
         [{"buffer": 0, "byteOffset": 0, "byteLength": pos_len}] +
         ([{"buffer": 0, "byteOffset": pos_len, "byteLength": len(bin_) - pos_len}]
          if indices is not None else []),
         "accessors": accessors if accessors is not None else
         [{"bufferView": 0, "componentType": 5126, "count": len(positions) // 3, "type": "VEC3"}] +
         ([{"bufferView": 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"}]
          if indices is not None else []),
         "meshes": [{"primitives": [primitive if primitive is not None else
                                    dict({"attributes": {"POSITION": 0}},
                                         **({"indices": 1} if indices is not None else {}))]}],
         "nodes": nodes if nodes is not None else [{"mesh": 0}],
         "scenes": [{"nodes": [0]}]}
    if not glb:
        import base64
        d["buffers"][0]["uri"] = "data:application/octet-stream;base64," + \
            base64.b64encode(bin_).decode()
    d.update(extra or {})
    return d, bin_


def glb_bytes(d, bin_):
    import json
    import struct
    j = json.dumps(d).encode()
    j += b" " * (-len(j) % 4)
    b = bin_ + b"\0" * (-len(bin_) % 4)
    return (b"glTF" + struct.pack("<II", 2, 12 + 8 + len(j) + 8 + len(b)) +
            struct.pack("<I", len(j)) + b"JSON" + j + struct.pack("<I", len(b)) + b"BIN\0" + b)


def gltf_text(**kw):
    import json
    return json.dumps(gltf_json(**kw)[0], indent=1)


def gltf():
    valid = gltf_text()
    ok("gltf_minimal", "gltf", "quiet: true\nfaces: 1\n", gltf=valid)
    ok("glb_minimal", "glb", "quiet: true\nfaces: 1\n", glb=glb_bytes(*gltf_json(glb=True)))
    # Broken JSON and binary containers.
    error("gltf_truncated_json", "gltf", "", gltf=valid[: len(valid) // 2])
    error("gltf_not_json", "gltf", "", gltf="this is not JSON\n")
    error("gltf_empty", "gltf", "file is empty", gltf="")
    error("gltf_json_array", "gltf", "", gltf="[1, 2, 3]\n")
    error("gltf_no_asset", "gltf", "", gltf='{"meshes": []}\n')
    good_glb = glb_bytes(*gltf_json(glb=True))
    error("glb_header_only", "glb", "", glb=good_glb[:12])
    error("glb_length_too_large", "glb", "",
          glb=good_glb[:8] + (len(good_glb) + 100).to_bytes(4, "little") + good_glb[12:])
    error("glb_json_chunk_too_long", "glb", "",
          glb=good_glb[:12] + (1 << 30).to_bytes(4, "little") + good_glb[16:])
    error("glb_truncated", "glb", "", glb=good_glb[: len(good_glb) - 10])
    # Version 1 of the binary container is glTF 1.0's.
    error("glb_version_1", "glb", "glTF 1.0 is not supported",
          glb=good_glb[:4] + (1).to_bytes(4, "little") + good_glb[8:])
    error("glb_not_glb", "glb", "", glb=b"\x00\x01garbage bytes\xff\xfe")
    # Accessors and buffer views.
    error("gltf_accessor_out_of_range", "gltf", "accessor 7 does not exist",
          gltf=gltf_text(primitive={"attributes": {"POSITION": 7}}))
    # tinygltf drops an attribute whose accessor is negative.
    error("gltf_accessor_negative", "gltf", "attributes.POSITION is -2",
          gltf=gltf_text(primitive={"attributes": {"POSITION": -2}}))
    error("gltf_buffer_view_beyond_buffer", "gltf", "lies beyond its buffer",
          gltf=gltf_text(views=[{"buffer": 0, "byteOffset": 24, "byteLength": 36}]))
    error("gltf_buffer_view_bad_buffer", "gltf", "",
          gltf=gltf_text(views=[{"buffer": 3, "byteLength": 36}]))
    error("gltf_accessor_beyond_view", "gltf", "lie beyond bufferView 0",
          gltf=gltf_text(accessors=[{"bufferView": 0, "componentType": 5126, "count": 4,
                                     "type": "VEC3"}]))
    error("gltf_accessor_offset_beyond_view", "gltf", "lie beyond bufferView 0",
          gltf=gltf_text(accessors=[{"bufferView": 0, "byteOffset": 4000000000,
                                     "componentType": 5126, "count": 3, "type": "VEC3"}]))
    error("gltf_huge_count", "gltf", "is too large",
          gltf=gltf_text(accessors=[{"bufferView": 0, "componentType": 5126,
                                     "count": 4000000000, "type": "VEC3"}]))
    error("gltf_position_unsigned_int", "gltf", "components are unsigned int, expected float",
          gltf=gltf_text(accessors=[{"bufferView": 0, "componentType": 5125, "count": 3,
                                     "type": "VEC3"}]))
    error("gltf_position_vec2", "gltf", "expected 3",
          gltf=gltf_text(accessors=[{"bufferView": 0, "componentType": 5126, "count": 3,
                                     "type": "VEC2"}]))
    error("gltf_unknown_component_type", "gltf", "",
          gltf=gltf_text(accessors=[{"bufferView": 0, "componentType": 9999, "count": 3,
                                     "type": "VEC3"}]))
    error("gltf_sparse_accessor", "gltf", "sparse accessors are not supported",
          gltf=gltf_text(accessors=[{"bufferView": 0, "componentType": 5126, "count": 3,
                                     "type": "VEC3", "sparse": {
                                         "count": 1,
                                         "indices": {"bufferView": 0, "componentType": 5125},
                                         "values": {"bufferView": 0}}}]))
    error("gltf_no_position", "gltf", "has no POSITION attribute",
          gltf=gltf_text(primitive={"attributes": {}}))
    error("gltf_index_out_of_range", "gltf", "index 2 is 5, but there are only 3 vertices",
          gltf=gltf_text(indices=[0, 1, 5]))
    error("gltf_nan_position", "gltf", "POSITION 1 is not a finite float",
          gltf=gltf_text(positions=(0, 0, 0, float("nan"), 0, 0, 0, 1, 0)))
    error("gltf_scale_overflows", "gltf", "is not a finite float",
          gltf=gltf_text(nodes=[{"mesh": 0, "scale": [1e38, 1e38, 1e38]},]).replace(
              "1e+38", "1e+300"))
    ok("gltf_some_degenerate", "gltf", "faces: 1\ndegenerate: 1\n",
       gltf=gltf_text(positions=(0, 0, 0, 1, 0, 0, 0, 1, 0), indices=[0, 1, 2, 0, 0, 1]))
    error("gltf_all_degenerate", "gltf", "all 1 triangles are degenerate",
          gltf=gltf_text(positions=(0, 0, 0, 1, 0, 0, 2, 0, 0)))
    # Files named by URIs.
    missing_bin, _ = gltf_json()
    missing_bin["buffers"][0]["uri"] = "missing.bin"
    import json
    error("gltf_missing_buffer_file", "gltf", "buffers[0].uri: 'missing.bin': file not found", gltf=json.dumps(missing_bin))
    missing_bin["buffers"][0]["uri"] = "."
    error("gltf_buffer_is_directory", "gltf", "", gltf=json.dumps(missing_bin))
    missing_bin["buffers"][0]["uri"] = "../hostile/gltf_minimal.gltf"
    error("gltf_buffer_wrong_size", "gltf", "", gltf=json.dumps(missing_bin))
    textured = {"materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
                "textures": [{"source": 0}], "images": [{"uri": "missing.png"}]}
    tri_mat = {"attributes": {"POSITION": 0}, "material": 0}
    error("gltf_missing_image", "gltf", "image 0: missing.png: No such file or directory",
          gltf=gltf_text(extra=textured, primitive=tri_mat))
    error("gltf_image_is_directory", "gltf", "image 0: .: is a directory",
          gltf=gltf_text(extra=dict(textured, images=[{"uri": "."}]), primitive=tri_mat))
    error("gltf_image_buffer_view_beyond_buffer", "gltf", "image 0: bufferView 1",
          gltf=gltf_text(extra=dict(textured, images=[{"bufferView": 1, "mimeType": "image/png"}]),
                         primitive=tri_mat,
                         views=[{"buffer": 0, "byteLength": 36},
                                {"buffer": 0, "byteOffset": 30, "byteLength": 100}]))
    error("gltf_texture_out_of_range", "gltf", "texture 0 does not exist",
          gltf=gltf_text(extra=dict(textured, textures=[]), primitive=tri_mat))
    error("gltf_image_out_of_range", "gltf", "image 4 does not exist",
          gltf=gltf_text(extra=dict(textured, textures=[{"source": 4}]), primitive=tri_mat))
    error("gltf_material_out_of_range", "gltf", "material 0 does not exist",
          gltf=gltf_text(primitive=tri_mat))
    error("gltf_metallic_2", "gltf", "metallicFactor is 2",
          gltf=gltf_text(extra={"materials": [{"pbrMetallicRoughness": {"metallicFactor": 2}}]},
                         primitive=tri_mat))
    # The node graph.
    error("gltf_node_cycle", "gltf", "is its own descendant",
          gltf=gltf_text(nodes=[{"mesh": 0, "children": [1]}, {"children": [0]}]))
    error("gltf_node_own_child", "gltf", "node #0 is its own descendant",
          gltf=gltf_text(nodes=[{"mesh": 0, "children": [0]}]))
    error("gltf_node_out_of_range", "gltf", "node 9 does not exist",
          gltf=gltf_text(nodes=[{"mesh": 0, "children": [9]}]))
    error("gltf_deep_nodes", "gltf", "nested more than 1024 deep",
          gltf=gltf_text(nodes=[{"children": [i + 1]} for i in range(2000)] + [{"mesh": 0}]))
    # Nodes shared by two parents at each of 40 levels: 2^40 paths to the last.
    def doubling(levels, first, last):
        """Level i holds nodes first + 2i and first + 2i + 1, each a parent of both nodes of
        level i + 1; the last level's nodes are `last`."""
        out = []
        for i in range(levels):
            nxt = [first + 2 * i + 2, first + 2 * i + 3]
            out += [{"children": nxt}, {"children": nxt}]
        return out + [dict(last), dict(last)]
    error("gltf_shared_nodes_explode", "gltf", "node instances",
          gltf=gltf_text(nodes=doubling(40, 0, {"mesh": 0})))
    error("gltf_shared_empty_nodes_explode", "gltf", "node instances",
          gltf=gltf_text(nodes=[{"mesh": 0, "children": [1, 2]}] + doubling(40, 1, {})))
    error("gltf_default_scene_out_of_range", "gltf", "scene 5 does not exist",
          gltf=gltf_text(extra={"scene": 5}))
    error("gltf_matrix_15_numbers", "gltf", "matrix has 15 elements, expected 16",
          gltf=gltf_text(nodes=[{"mesh": 0, "matrix": [1] * 15}]))
    error("gltf_zero_quaternion", "gltf", "rotation is a zero quaternion",
          gltf=gltf_text(nodes=[{"mesh": 0, "rotation": [0, 0, 0, 0]}]))
    error("gltf_mesh_out_of_range", "gltf", "mesh 3 does not exist",
          gltf=gltf_text(nodes=[{"mesh": 3}]))
    ok("gltf_no_scenes", "gltf", "quiet: true\nfaces: 1\n",
       gltf=gltf_text(extra={"scenes": []}))
    # Primitive modes.
    ok("gltf_points_and_triangles", "gltf", "faces: 1\nwarning: mode 0 (points or lines) is skipped\n",
       gltf=gltf_text(extra={"meshes": [{"primitives": [
           {"attributes": {"POSITION": 0}, "mode": 0}, {"attributes": {"POSITION": 0}}]}]}))
    error("gltf_only_lines", "gltf", "no triangles in the scene",
          gltf=gltf_text(primitive={"attributes": {"POSITION": 0}, "mode": 1}))
    ok("gltf_triangle_fan", "gltf", "quiet: true\nfaces: 2\n",
       gltf=gltf_text(positions=(0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0),
                      primitive={"attributes": {"POSITION": 0}, "mode": 6}))
    # Cameras and lights.
    error("gltf_camera_out_of_range", "gltf", "camera 2 does not exist",
          gltf=gltf_text(nodes=[{"mesh": 0, "children": [1]}, {"camera": 2}]))
    error("gltf_yfov_zero", "gltf", "perspective.yfov is 0, expected > 0",
          gltf=gltf_text(extra={"cameras": [{"type": "perspective",
                                             "perspective": {"yfov": 0, "znear": 0.1}}]},
                         nodes=[{"mesh": 0, "children": [1]}, {"camera": 0}]))
    ok("gltf_orthographic_camera", "gltf",
       "faces: 1\nwarning: rendered as a perspective camera of 60 degrees\n",
       gltf=gltf_text(extra={"cameras": [{"type": "orthographic", "orthographic": {
           "xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 100}}]},
           nodes=[{"mesh": 0, "children": [1]}, {"camera": 0, "translation": [0, 0, 5]}]))
    lights = {"extensionsUsed": ["KHR_lights_punctual"],
              "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point",
                                                                 "intensity": 10}]}}}
    error("gltf_light_out_of_range", "gltf", "KHR_lights_punctual light 3 does not exist",
          gltf=gltf_text(extra=lights, nodes=[{"mesh": 0, "children": [1]}, {
              "extensions": {"KHR_lights_punctual": {"light": 3}}}]))
    ok("gltf_directional_light", "gltf", "faces: 1\nwarning: placed as a point light far away\n",
       gltf=gltf_text(extra={"extensions": {"KHR_lights_punctual": {"lights": [
           {"type": "directional", "intensity": 3}]}}},
           nodes=[{"mesh": 0, "children": [1]}, {
               "extensions": {"KHR_lights_punctual": {"light": 0}}}]))


def gltf_assets():
    """glTF as the tools write it and as an attacker would: extensions, glTF 1.0, JSON bombs,
    schema violations, files outside the asset's folder, compressed data that lies."""
    import json
    tri_mat = {"attributes": {"POSITION": 0}, "material": 0}
    error("gltf_deep_json", "gltf", "JSON nests arrays and objects more than 128 deep",
          gltf='{"asset":{"version":"2.0"},"extras":' + "[" * 100000 + "]" * 100000 + "}")
    error("gltf_deep_json_unclosed", "gltf", "more than 128 deep", gltf="{" * 100000)
    error("gltf_version_1", "gltf", "glTF 1.0 is not supported (asset.version '1.0')",
          gltf='{"asset": {"version": "1.0"}, "meshes": {"m": {"primitives": []}}}\n')
    error("gltf_version_1_keyed", "gltf", "glTF 1.0 is not supported",
          gltf='{"meshes": {"m": {"primitives": []}}}\n')
    error("gltf_required_unknown", "gltf", "requires extension EXT_unknown_thing",
          gltf=gltf_text(extra={"extensionsUsed": ["EXT_unknown_thing"],
                                "extensionsRequired": ["EXT_unknown_thing"]}))
    ok("gltf_used_unknown", "gltf", "faces: 1\nwarning: ignores extension VENDOR_thing\n",
       gltf=gltf_text(extra={"extensionsUsed": ["VENDOR_thing"]}))
    error("gltf_negative_byte_stride", "gltf", "bufferViews[0].byteStride is -12",
          gltf=gltf_text(views=[{"buffer": 0, "byteLength": 36, "byteStride": -12}]))
    error("gltf_negative_byte_offset", "gltf", "bufferViews[0].byteOffset is -4",
          gltf=gltf_text(views=[{"buffer": 0, "byteOffset": -4, "byteLength": 36}]))
    error("gltf_base_color_5_numbers", "gltf", "baseColorFactor has 5 elements, expected 4",
          gltf=gltf_text(extra={"materials": [{"pbrMetallicRoughness": {
              "baseColorFactor": [1, 1, 1, 1, 1]}}]}, primitive=tri_mat))
    error("gltf_name_is_number", "gltf", "scenes[0].name is a number, expected a string",
          gltf=gltf_text(extra={"scenes": [{"nodes": [0], "name": 42}]}))
    two, bin_ = gltf_json(glb=True)
    two["buffers"].append({"byteLength": len(bin_)})
    error("glb_second_buffer_without_uri", "glb",
          "buffers[1] has no uri: only the first buffer of a GLB may use its BIN chunk",
          glb=glb_bytes(two, bin_))
    textured = {"materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
                "textures": [{"source": 0}]}
    for name, uri, message in [
            ("gltf_image_outside", "../outside/secret.png", "lies outside the folder"),
            ("gltf_image_absolute", "/etc/hostname", "lies outside the folder"),
            ("gltf_image_encoded_dots", "%2E%2E/%2E%2E/etc/hostname", "lies outside the folder"),
            ("gltf_image_http", "http://example.com/a.png", "is a URI with scheme 'http'")]:
        error(name, "gltf", message,
              gltf=gltf_text(extra=dict(textured, images=[{"uri": uri}]), primitive=tri_mat))
    passwd, _ = gltf_json()
    passwd["buffers"][0]["uri"] = "../" * 12 + "etc/passwd"
    error("gltf_buffer_passwd", "gltf", "buffers[0].uri: '../../", gltf=json.dumps(passwd))
    lights = {"extensionsUsed": ["KHR_lights_punctual"],
              "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point"}]}}}
    light_node = {"extensions": {"KHR_lights_punctual": {"light": 0}}}
    levels = []
    for i in range(12):
        nxt = [1 + 2 * i + 2, 1 + 2 * i + 3]
        levels += [{"children": nxt}, {"children": nxt}]
    error("gltf_light_instances", "gltf", "more than 4096 light instances",
          gltf=gltf_text(extra=lights, nodes=[{"mesh": 0, "children": [1, 2]}] + levels +
                         [light_node, light_node]))
    # EXT_meshopt_compression and KHR_draco_mesh_compression whose data lies.
    meshopt, bin_ = gltf_json()
    meshopt.update({"extensionsUsed": ["EXT_meshopt_compression"],
                    "extensionsRequired": ["EXT_meshopt_compression"]})
    meshopt["buffers"].append({"byteLength": 36,
                               "extensions": {"EXT_meshopt_compression": {"fallback": True}}})
    meshopt["bufferViews"] = [{"buffer": 1, "byteLength": 36, "byteStride": 12, "extensions": {
        "EXT_meshopt_compression": {"buffer": 0, "byteLength": 36, "byteStride": 12,
                                    "mode": "ATTRIBUTES", "count": 3}}}]
    error("gltf_meshopt_garbage", "gltf", "the compressed data is malformed (meshoptimizer",
          gltf=json.dumps(meshopt))
    meshopt["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 1 << 40
    error("gltf_meshopt_huge_count", "gltf", "is too large", gltf=json.dumps(meshopt))
    meshopt["bufferViews"][0]["extensions"]["EXT_meshopt_compression"].update(
        {"count": 3, "byteOffset": 1 << 40})
    error("gltf_meshopt_beyond_buffer", "gltf", "lie beyond buffer 0", gltf=json.dumps(meshopt))
    draco, bin_ = gltf_json()
    draco.update({"extensionsUsed": ["KHR_draco_mesh_compression"],
                  "extensionsRequired": ["KHR_draco_mesh_compression"]})
    draco["accessors"] = [{"componentType": 5126, "count": 3, "type": "VEC3"}]
    draco["meshes"][0]["primitives"][0]["extensions"] = {"KHR_draco_mesh_compression": {
        "bufferView": 0, "attributes": {"POSITION": 0}}}
    error("gltf_draco_garbage", "gltf", "the compressed data is malformed (Draco",
          gltf=json.dumps(draco))


# ---- glTF animations -------------------------------------------------------------------------

def gltf_animation(channels, samplers, times=(0.0, 1.0), values=(0, 0, 0, 1, 2, 3),
                   values_type="VEC3", values_component=5126, nodes=None, times_component=5126):
    """The one-triangle glTF with an animation: accessor 1 holds `times`, accessor 2 `values`
    (floats unless `values_component` says otherwise)."""
    import math
    import struct
    positions = (0, 0, 0, 1, 0, 0, 0, 1, 0)
    d, bin_ = gltf_json(positions=positions, nodes=nodes)
    t = b"".join(struct.pack("<f" if times_component == 5126 else "<H",
                             x if times_component == 5126 else int(x)) for x in times)
    while len(t) % 4:
        t += b"\0"
    fmt = {5126: "<f", 5120: "<b", 5122: "<h"}[values_component]
    v = b"".join(struct.pack(fmt, x) for x in values)
    while len(v) % 4:
        v += b"\0"
    t_off = len(bin_)
    bin_ = bin_ + t + v
    width = {"VEC3": 3, "VEC4": 4, "SCALAR": 1}[values_type]
    d["bufferViews"] += [{"buffer": 0, "byteOffset": t_off, "byteLength": len(t)},
                         {"buffer": 0, "byteOffset": t_off + len(t), "byteLength": len(v)}]
    d["accessors"] += [{"bufferView": 1, "componentType": times_component, "count": len(times),
                        "type": "SCALAR"},
                       dict({"bufferView": 2, "componentType": values_component,
                             "count": len(values) // width, "type": values_type},
                            **({"normalized": True} if values_component != 5126 else {}))]
    import base64
    d["buffers"] = [{"byteLength": len(bin_), "uri": "data:application/octet-stream;base64," +
                     base64.b64encode(bin_).decode()}]
    d["animations"] = [{"channels": channels, "samplers": samplers}]
    import json
    return json.dumps(d, indent=1)


def gltf_animations():
    """Malformed animation data: one clear line each; a weights channel only warns."""
    nan = float("nan")
    move = [{"sampler": 0, "target": {"node": 0, "path": "translation"}}]
    turn = [{"sampler": 0, "target": {"node": 0, "path": "rotation"}}]
    linear = [{"input": 1, "output": 2}]
    ok("gltf_anim_translation", "gltf", "quiet: true\nfaces: 1\n",
       gltf=gltf_animation(move, linear))
    for name, message, kw in [
        ("gltf_anim_times_not_increasing", "key times must increase",
         dict(times=(0.0, 1.0, 1.0), values=(0,) * 9)),
        ("gltf_anim_times_decreasing", "input key 1 (0.5 s) does not come after key 0",
         dict(times=(1.0, 0.5), values=(0,) * 6)),
        ("gltf_anim_time_nan", "input key 1 is nan", dict(times=(0.0, nan), values=(0,) * 6)),
        ("gltf_anim_value_nan", "output element 1 holds nan",
         dict(values=(0, 0, 0, 1, nan, 3))),
        ("gltf_anim_value_infinite", "output element 0 holds inf",
         dict(values=(float("inf"), 0, 0, 1, 2, 3))),
        ("gltf_anim_output_count", "output has 1 elements for 2 keys, expected 2",
         dict(values=(0, 0, 0))),
        ("gltf_anim_times_integers", "input", dict(times_component=5123)),
        ("gltf_anim_no_keys", "accessors[1].count is 0", dict(times=(), values=())),
    ]:
        error(name, "gltf", message, gltf=gltf_animation(move, linear, **kw))
    error("gltf_anim_cubic_count", "gltf", "(CUBICSPLINE: in-tangent, value, out-tangent per key)",
          gltf=gltf_animation(move, [{"input": 1, "output": 2, "interpolation": "CUBICSPLINE"}]))
    error("gltf_anim_interpolation_unknown", "gltf",
          "animations[0].samplers[0].interpolation is 'BEZIER', expected one of",
          gltf=gltf_animation(move, [{"input": 1, "output": 2, "interpolation": "BEZIER"}]))
    error("gltf_anim_path_unknown", "gltf", "animations[0].channels[0].target.path is 'colour'",
          gltf=gltf_animation([{"sampler": 0, "target": {"node": 0, "path": "colour"}}], linear))
    error("gltf_anim_no_channels", "gltf", "animations[0].channels has 0 elements",
          gltf=gltf_animation([], linear))
    error("gltf_anim_node_out_of_range", "gltf", "node 9 does not exist",
          gltf=gltf_animation([{"sampler": 0, "target": {"node": 9, "path": "scale"}}], linear))
    error("gltf_anim_sampler_out_of_range", "gltf", "sampler 5 does not exist (1 samplers)",
          gltf=gltf_animation([{"sampler": 5, "target": {"node": 0, "path": "scale"}}], linear))
    error("gltf_anim_sampler_negative", "gltf", "animations[0].channels[0].sampler is -1",
          gltf=gltf_animation([{"sampler": -1, "target": {"node": 0, "path": "scale"}}], linear))
    error("gltf_anim_output_accessor_missing", "gltf", "accessor 7 does not exist",
          gltf=gltf_animation(move, [{"input": 1, "output": 7}]))
    error("gltf_anim_same_target_twice", "gltf", "is the target of an earlier channel",
          gltf=gltf_animation(move + move, linear))
    error("gltf_anim_node_with_matrix", "gltf", "has a matrix",
          gltf=gltf_animation(move, linear,
                              nodes=[{"mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0,
                                                            0, 0, 0, 1]}]))
    error("gltf_anim_zero_quaternion", "gltf", "output element 1 is a zero quaternion",
          gltf=gltf_animation(turn, linear, values=(0, 0, 0, 1, 0, 0, 0, 0), values_type="VEC4"))
    error("gltf_anim_rotation_vec3", "gltf", "output",
          gltf=gltf_animation(turn, linear))
    ok("gltf_anim_rotation_normalized_shorts", "gltf", "quiet: true\nfaces: 1\n",
       gltf=gltf_animation(turn, linear, values=(0, 0, 0, 32767, 0, 32767, 0, 0),
                           values_type="VEC4", values_component=5122))
    error("gltf_anim_rotation_shorts_not_normalized", "gltf", "integer rotations must be normalized",
          gltf=gltf_animation(turn, linear, values=(0, 0, 0, 32767, 0, 32767, 0, 0),
                              values_type="VEC4", values_component=5122).replace(
                                  '"normalized": true', '"normalized": false'))
    ok("gltf_anim_pointer_still", "gltf",
       "warning: animated pointer stay still\nfaces: 1\n",
       gltf=gltf_animation([{"sampler": 0, "target": {"node": 0, "path": "pointer"}}],
                           [{"input": 1, "output": 2}]))
    ok("gltf_anim_channel_without_node", "gltf", "quiet: true\nfaces: 1\n",
       gltf=gltf_animation([{"sampler": 0, "target": {"path": "translation"}}], linear))



def gltf_morph(targets, weights_node=None, weights_mesh=None, extra_positions=(), animation=None,
               more_nodes=(), accessors_extra=()):
    """The one-triangle glTF whose primitive has `targets` (each a dict of attribute to
    accessor; accessor 0 is the triangle's positions, accessor 1 holds `extra_positions`);
    node 0 has the mesh."""
    import json
    positions = (0, 0, 0, 1, 0, 0, 0, 1, 0) + tuple(extra_positions)
    d, bin_ = gltf_json(positions=positions)
    d["accessors"][0]["count"] = 3
    if extra_positions:
        d["bufferViews"][0]["byteLength"] = 36
        d["bufferViews"].append({"buffer": 0, "byteOffset": 36, "byteLength": len(extra_positions) * 4})
        d["accessors"].append({"bufferView": 1, "componentType": 5126,
                               "count": len(extra_positions) // 3, "type": "VEC3"})
    d["accessors"] += list(accessors_extra)
    d["meshes"][0]["primitives"][0]["targets"] = targets
    if weights_mesh is not None:
        d["meshes"][0]["weights"] = weights_mesh
    if weights_node is not None:
        d["nodes"][0]["weights"] = weights_node
    d["nodes"] += list(more_nodes)
    if animation is not None:
        d["animations"] = [animation]
    return json.dumps(d, indent=1)


def gltf_morphs():
    """Morph targets and their weights: one clear line each."""
    two = [{"POSITION": 0}, {"POSITION": 0}]
    ok("gltf_morph_two_targets", "gltf", "quiet: true\nfaces: 1\n",
       gltf=gltf_morph(two, weights_node=[0.5, 0.25]))
    error("gltf_morph_node_weights_count", "gltf", "the node has 1 morph target weights, its mesh 2",
          gltf=gltf_morph(two, weights_node=[1]))
    error("gltf_morph_mesh_weights_count", "gltf", "has 3 morph target weights, its mesh 2 targets",
          gltf=gltf_morph(two, weights_mesh=[1, 2, 3]))
    error("gltf_morph_target_count", "gltf", "target 0 POSITION has 4 elements, POSITION 3",
          gltf=gltf_morph([{"POSITION": 1}], weights_node=[1],
                          extra_positions=(0, 0, 1) * 4))
    error("gltf_morph_target_missing_accessor", "gltf", "accessor 9 does not exist",
          gltf=gltf_morph([{"POSITION": 9}], weights_node=[1]))
    error("gltf_morph_displacement_overflows", "gltf", "POSITION 0 is not a finite float",
          gltf=gltf_morph([{"POSITION": 1}], weights_node=[10],
                          extra_positions=(3e38, 0, 0) * 3))
    error("gltf_morph_integer_not_normalized", "gltf", "integer displacements must be normalized",
          gltf=gltf_morph([{"POSITION": 1}], weights_node=[1],
                          accessors_extra=[{"bufferView": 0, "componentType": 5122, "count": 3,
                                            "type": "VEC3"}]))
    anim = lambda node, output_count: {  # noqa: E731
        "channels": [{"sampler": 0, "target": {"node": node, "path": "weights"}}],
        "samplers": [{"input": 1, "output": 2}]}
    # accessors 1 and 2 of the animations: 2 times, then weights (floats of the positions)
    times_and_weights = [{"bufferView": 0, "componentType": 5126, "count": 2, "type": "SCALAR"},
                         {"bufferView": 0, "componentType": 5126, "count": 3, "type": "SCALAR"}]
    error("gltf_morph_weights_output_count", "gltf",
          "output has 3 elements for 2 keys, expected 4 (2 morph target weights per key)",
          gltf=gltf_morph(two, animation=anim(0, 3), accessors_extra=times_and_weights))
    error("gltf_morph_weights_of_a_mesh_without_targets", "gltf", "whose mesh has no morph targets",
          gltf=gltf_morph([], animation=anim(0, 3), accessors_extra=times_and_weights))
    error("gltf_morph_weights_of_a_node_without_mesh", "gltf", "which has no mesh",
          gltf=gltf_morph(two, animation=anim(1, 3), more_nodes=[{}],
                          accessors_extra=times_and_weights))



# ---- physically based materials and environments ------------------------------------------

def pbr():
    """model = "pbr" materials and [environment]: keys of the other model, ranges, files."""
    for name, toml, message, line in [
        ("pbr_phong_key_in_pbr", CAMERA + '[materials.m]\nmodel = "pbr"\nshininess = 10\n',
         "unknown key 'shininess' in materials.m", 6),
        ("pbr_pbr_key_in_phong", CAMERA + "[materials.m]\ndiffuse = [1, 1, 1]\nmetallic = 1\n",
         "unknown key 'metallic' in materials.m", 6),
        ("pbr_unknown_model", CAMERA + '[materials.m]\nmodel = "blinn"\n',
         'materials.m.model must be "phong" or "pbr"', 5),
        ("pbr_metallic_out_of_range", CAMERA + '[materials.m]\nmodel = "pbr"\nmetallic = 1.5\n',
         "materials.m.metallic must be in [0, 1]", 6),
        ("pbr_texture_missing",
         CAMERA + '[materials.m]\nmodel = "pbr"\nbase_color_texture = "textures/none.png"\n',
         "none.png': no such file", 6),
        ("environment_sun_zero", CAMERA + "[environment]\nsun_direction = [0, 0, 0]\n",
         "environment.sun_direction must not be zero", 5),
        ("environment_image_is_a_directory", CAMERA + '[environment]\nimage = "."\n',
         "is not a readable file", 5),
    ]:
        scene_error(name, toml, message, line)


# ---- glTF skins ------------------------------------------------------------------------------

def gltf_skin(joints=(0, 0, 0, 0) * 3, weights=(1, 0, 0, 0) * 3, weights_component=5126,
              ibm=(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1), ibm_type="MAT4",
              skin=None, nodes=None, attributes=None, normalized=True):
    """The one-triangle glTF skinned by one joint (node 1): accessor 1 holds JOINTS_0 (unsigned
    bytes), 2 WEIGHTS_0 (floats unless `weights_component` says otherwise), 3 `ibm` (floats,
    of `ibm_type`); node 0 has the mesh and skin 0."""
    import base64
    import json
    import struct
    d, bin_ = gltf_json()
    fmt = {5126: "<f", 5121: "<B", 5123: "<H"}[weights_component]
    parts = [bytes(joints), b"".join(struct.pack(fmt, x) for x in weights),
             struct.pack(f"<{len(ibm)}f", *ibm)]
    width = {"MAT4": 16, "VEC4": 4}[ibm_type]
    for i, (part, component, type_, count) in enumerate([
            (parts[0], 5121, "VEC4", len(joints) // 4),
            (parts[1], weights_component, "VEC4", len(weights) // 4),
            (parts[2], 5126, ibm_type, len(ibm) // width)]):
        while len(part) % 4:
            part += b"\0"
        d["bufferViews"].append({"buffer": 0, "byteOffset": len(bin_), "byteLength": len(part)})
        d["accessors"].append(dict({"bufferView": i + 1, "componentType": component,
                                    "count": count, "type": type_},
                                   **({"normalized": True} if i == 1 and component != 5126
                                      and normalized else {})))
        bin_ += part
    d["buffers"] = [{"byteLength": len(bin_), "uri": "data:application/octet-stream;base64," +
                     base64.b64encode(bin_).decode()}]
    d["meshes"][0]["primitives"][0]["attributes"] = attributes if attributes is not None else \
        {"POSITION": 0, "JOINTS_0": 1, "WEIGHTS_0": 2}
    d["skins"] = [skin if skin is not None else {"joints": [1], "inverseBindMatrices": 3}]
    d["nodes"] = nodes if nodes is not None else [{"mesh": 0, "skin": 0}, {"translation": [1, 2, 3]}]
    d["scenes"] = [{"nodes": [0, 1]}] if len(d["nodes"]) > 1 else [{"nodes": [0]}]
    return json.dumps(d, indent=1)


def gltf_skins():
    """Malformed skins and skinned primitives: one clear line each."""
    nan = float("nan")
    ok("gltf_skin_one_joint", "gltf", "quiet: true\nfaces: 1\n", gltf=gltf_skin())
    ok("gltf_skin_weights_normalized_bytes", "gltf", "quiet: true\nfaces: 1\n",
       gltf=gltf_skin(weights=(254, 0, 0, 0) * 3, weights_component=5121))
    ok("gltf_skin_node_without_mesh", "gltf", "quiet: true\nfaces: 1\n",
       gltf=gltf_skin(nodes=[{"mesh": 0}, {"skin": 0}]))
    for name, message, kw in [
        ("gltf_skin_joint_index_out_of_range",
         "JOINTS_0 1 names joint 3, but skin #0 has 1 joints",
         dict(joints=(0, 0, 0, 0, 0, 3, 0, 0, 0, 0, 0, 0), weights=(1, 0, 0, 0, 0.5, 0.5, 0, 0) +
              (1, 0, 0, 0))),
        ("gltf_skin_weights_sum", "WEIGHTS_0 0 sums to 0.75, expected 1 (within 0.002)",
         dict(weights=(0.5, 0.25, 0, 0) * 3)),
        ("gltf_skin_weights_bytes_sum", "WEIGHTS_0 0 sums to 0.97647",
         dict(weights=(249, 0, 0, 0) * 3, weights_component=5121)),
        ("gltf_skin_weights_bytes_not_normalized", "WEIGHTS_0: integer weights must be normalized",
         dict(weights=(255, 0, 0, 0) * 3, weights_component=5121, normalized=False)),
        ("gltf_skin_weight_negative", "WEIGHTS_0 0 holds -0.5, expected a weight >= 0",
         dict(weights=(1.5, -0.5, 0, 0) * 3)),
        ("gltf_skin_weight_nan", "WEIGHTS_0 2 holds nan", dict(weights=(1, 0, 0, 0) * 2 + (nan, 1, 0, 0))),
        ("gltf_skin_ibm_nan", "skin #0 inverseBindMatrices element 0 holds nan",
         dict(ibm=(1, 0, 0, 0, 0, nan, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1))),
        ("gltf_skin_ibm_infinite", "skin #0 inverseBindMatrices element 0 holds inf",
         dict(ibm=(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, float("inf"), 0, 0, 1))),
        ("gltf_skin_ibm_not_affine",
         "skin #0 inverseBindMatrices element 0 is not affine (its last row is 0 0 1 1, expected 0 0 0 1)",
         dict(ibm=(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 1))),
        ("gltf_skin_ibm_vec4", "skin #0 inverseBindMatrices: accessor 3: has 4 components per "
         "element, expected 16", dict(ibm=(1, 0, 0, 0) * 4, ibm_type="VEC4")),
        ("gltf_skin_ibm_too_few", "skin #0 inverseBindMatrices has 1 elements, its skin 2 joints",
         dict(skin={"joints": [1, 2], "inverseBindMatrices": 3},
              nodes=[{"mesh": 0, "skin": 0}, {"children": [2]}, {}])),
        ("gltf_skin_ibm_missing", "skin #0 inverseBindMatrices: accessor 9 does not exist",
         dict(skin={"joints": [1], "inverseBindMatrices": 9})),
        ("gltf_skin_joint_node_out_of_range", "skin #0: joints[1]: node 7 does not exist (2 nodes)",
         dict(skin={"joints": [1, 7]})),
        ("gltf_skin_joints_empty", "skins[0].joints has 0 elements, expected 1 to 65536",
         dict(skin={"joints": []})),
        ("gltf_skin_joints_twice", "skins[0].joints names 1 twice", dict(skin={"joints": [1, 1]})),
        ("gltf_skin_joints_missing", "skins[0] has no 'joints', which glTF requires",
         dict(skin={"inverseBindMatrices": 3})),
        ("gltf_skin_out_of_range", "node #0: skin 4 does not exist (1 skins)",
         dict(nodes=[{"mesh": 0, "skin": 4}, {}])),
        ("gltf_skin_without_joints_attribute", "its node has skin #0, but it has no JOINTS_0 attribute",
         dict(attributes={"POSITION": 0, "WEIGHTS_0": 2})),
        ("gltf_skin_without_weights_attribute",
         "its node has skin #0, but it has no WEIGHTS_0 attribute",
         dict(attributes={"POSITION": 0, "JOINTS_0": 1})),
        ("gltf_skin_joints_1", "has JOINTS_1 or WEIGHTS_1; rt2 reads four joints a vertex",
         dict(attributes={"POSITION": 0, "JOINTS_0": 1, "WEIGHTS_0": 2, "JOINTS_1": 1,
                          "WEIGHTS_1": 2})),
        ("gltf_skin_joint_with_two_parents", "has several parents",
         dict(nodes=[{"mesh": 0, "skin": 0}, {}, {"children": [1]}, {"children": [1]}])),
    ]:
        error(name, "gltf", message, gltf=gltf_skin(**kw))


def main():
    malformed_toml()
    fuzz_found()
    review_found()
    truncated()
    encodings()
    depth()
    obj_faces()
    mtl_values()
    numbers()
    keys()
    paths()
    pbr()
    sizes()
    gltf()
    gltf_assets()
    gltf_animations()
    gltf_morphs()
    gltf_skins()


if __name__ == "__main__":
    main()
