"""Shared machinery of rt2's experiment scripts (scripts/sweep-*, tradeoff, ...).

An experiment runs rt2cpr (or a benchmark program) many times, one measurement per run,
and writes results/<name>.csv — one row per measurement with every parameter, the median,
min and max fps over several frames, Mrays/s, the machine and the date — and
results/<name>.png, a gnuplot plot (pngcairo). Where the thesis has the same curve, its
numbers are overlaid normalised to their first point.

--quick (every script, and scripts/experiments) renders the presets at a quarter of their
width and height with fewer frames and fewer points, so that all experiments together
finish within 10 minutes on 2 cores. Standard library only: this runs on Debian's python3.
"""

import argparse
import csv
import datetime
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RESULTS = os.path.join(ROOT, "results")
PRESETS = ("low", "middle", "hard", "veryhard")
PRESET_SIZE = {"low": (512, 512), "middle": (800, 600), "hard": (1024, 768),
               "veryhard": (1920, 1080)}
_T0 = time.monotonic()
_BUILT = set()


class Options:
    """Command-line options every experiment shares."""

    def __init__(self, ns):
        self.quick = ns.quick
        self.frames = ns.frames or (2 if ns.quick else 5)
        self.presets = ns.presets.split(",") if ns.presets else list(PRESETS)
        self.scale = 4 if ns.quick else 1  # quick: a quarter of the width and height
        self.threads = ns.threads or os.cpu_count() or 2


def parse_args(description, add=None):
    p = argparse.ArgumentParser(description=description)
    p.add_argument("--quick", action="store_true",
                   help="quarter-size images, fewer frames and points (all experiments < 10 min)")
    p.add_argument("--frames", type=int, help="frames per measurement (default 5, quick 2)")
    p.add_argument("--presets", help="comma-separated subset of low,middle,hard,veryhard")
    p.add_argument("--threads", type=int, help="threads for runs that do not sweep them "
                   "(default: all cores)")
    if add:
        add(p)
    ns = p.parse_args()
    for preset in (ns.presets.split(",") if ns.presets else []):
        if preset not in PRESETS:
            p.error("unknown preset %r" % preset)
    return Options(ns), ns


def progress(msg):
    print("[%6.1fs] %s" % (time.monotonic() - _T0, msg), file=sys.stderr, flush=True)


def fail(msg):
    print("error: " + msg, file=sys.stderr)
    sys.exit(1)


def build(*targets, arch="sse41"):
    """Installs missing packages and builds `targets` (paths under build/...) once per run."""
    key = (arch,) + targets
    if key in _BUILT:
        return
    subprocess.run(["bash", "-c", ". scripts/lib/deps.sh && ensure_packages $RT2_BUILD_PACKAGES "
                    "gnuplot-nox"], cwd=ROOT, check=True)
    cmd = ["scons", "-Q", "-j%d" % (os.cpu_count() or 2), "mode=release", "arch=" + arch]
    progress("building " + " ".join(targets))
    r = subprocess.run(cmd + list(targets), cwd=ROOT, stdout=subprocess.DEVNULL)
    if r.returncode != 0:
        fail("build failed: " + " ".join(cmd + list(targets)))
    _BUILT.add(key)


def binary(name, arch="sse41"):
    folder = "release" if arch == "sse41" else "release-" + arch
    return os.path.join(ROOT, "build", folder, "bin", name)


def preset_args(preset, opts):
    """rt2cpr arguments for a preset, scaled down in --quick mode."""
    w, h = PRESET_SIZE[preset]
    return ["--preset", preset, "--width", str(w // opts.scale), "--height", str(h // opts.scale)]


def rt2cpr(args, frames, arch="sse41"):
    """Runs rt2cpr with `args` for `frames` frames and returns its --stats JSON."""
    exe = binary("rt2cpr", arch)
    build(os.path.relpath(exe, ROOT), arch=arch)
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "stats.json")
        cmd = [exe, "--quiet", "--frames", str(frames), "--stats", stats] + [str(a) for a in args]
        r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        if r.returncode != 0:
            fail("%s failed: %s" % (" ".join(cmd), r.stderr.strip()))
        with open(stats) as f:
            return json.load(f)


def machine():
    cpu = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return "%s, %d cores, %s" % (cpu, os.cpu_count() or 0, platform.node())


def measurement(stats):
    """The columns every rt2cpr measurement contributes."""
    return {"fps_median": round(stats["fps_median"], 4), "fps_min": round(stats["fps_min"], 4),
            "fps_max": round(stats["fps_max"], 4), "mrays_per_s": round(stats["mrays_per_s"], 3),
            "frame_ms_median": round(stats["frame_ms_median"], 3)}


class Results:
    """results/<name>.csv, rewritten after every row so an interrupted sweep keeps its data."""

    def __init__(self, name):
        os.makedirs(RESULTS, exist_ok=True)
        self.name = name
        self.path = os.path.join(RESULTS, name + ".csv")
        self.rows = []
        self.machine = machine()
        self.date = datetime.date.today().isoformat()

    def add(self, **row):
        row["machine"] = self.machine
        row["date"] = self.date
        self.rows.append(row)
        keys = []
        for r in self.rows:
            keys += [k for k in r if k not in keys]
        tmp = self.path + ".tmp"
        with open(tmp, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=keys)
            w.writeheader()
            w.writerows(self.rows)
        os.replace(tmp, self.path)
        return row

    def select(self, **where):
        return [r for r in self.rows if all(r.get(k) == v for k, v in where.items())]


def normalised(points):
    """Points divided by the first point's y (shapes compare across machines)."""
    if not points or points[0][1] == 0:
        return points
    y0 = points[0][1]
    return [(x, y / y0) for x, y in points]


class Series:
    def __init__(self, label, points, style="linespoints", dashed=False):
        self.label, self.points, self.style, self.dashed = label, points, style, dashed


class Panel:
    def __init__(self, title, xlabel, ylabel, series, logx=False, logy=False, extra=""):
        self.title, self.xlabel, self.ylabel = title, xlabel, ylabel
        self.series, self.logx, self.logy, self.extra = series, logx, logy, extra


def plot(name, title, panels, columns=2):
    """results/<name>.png with one panel per entry (a multiplot grid); the gnuplot script is
    kept beside it as results/<name>.gp."""
    rows = (len(panels) + columns - 1) // columns
    cols = min(columns, len(panels))
    lines = ['set terminal pngcairo noenhanced size %d,%d font "sans,10"' % (640 * cols, 460 * rows),
             'set output "%s"' % os.path.join(RESULTS, name + ".png"),
             'set multiplot layout %d,%d title "%s"' % (rows, cols, title.replace('"', "'")),
             "set grid", "set key top right font \",9\""]
    for pi, p in enumerate(panels):
        for si, s in enumerate(p.series):
            lines.append("$d%d_%d << EOD" % (pi, si))
            lines += ["%r %r" % (float(x), float(y)) for x, y in s.points]
            lines.append("EOD")
    for pi, p in enumerate(panels):
        lines += ['set title "%s"' % p.title, 'set xlabel "%s"' % p.xlabel,
                  'set ylabel "%s"' % p.ylabel,
                  "set logscale x" if p.logx else "unset logscale x",
                  "set logscale y" if p.logy else "unset logscale y"]
        if p.extra:
            lines.append(p.extra)
        plots = []
        for si, s in enumerate(p.series):
            dash = " dt 2" if s.dashed else ""
            plots.append('$d%d_%d with %s lw 2%s title "%s"' % (pi, si, s.style, dash, s.label))
        lines.append("plot " + ", ".join(plots) if plots else "plot NaN notitle")
    lines.append("unset multiplot")
    script = os.path.join(RESULTS, name + ".gp")
    with open(script, "w") as f:
        f.write("\n".join(lines) + "\n")
    r = subprocess.run(["gnuplot", script], capture_output=True, text=True)
    if r.returncode != 0:
        fail("gnuplot failed on %s: %s" % (script, r.stderr.strip()))
    progress("wrote results/%s.csv and results/%s.png" % (name, name))


def median(values):
    return statistics.median(values) if values else float("nan")


# --- the speed/accuracy experiments: scenes and their references -------------------------

# Built-in scene (mirrors), a glass scene, and a real mesh from Debian's libcgal-demo
# (scripts/fetch-meshes converts it).
MESH_SCENE = "data/meshes/bunny00-mirror.toml"
TRADE_SCENES = {"default": [], "glass": ["--scene", "scenes/glass.toml"],
                "mesh": ["--scene", MESH_SCENE]}
REFERENCE_SETTINGS = ["--subpixels", 64, "--depth", 32, "--min-weight", 0]


def trade_size(opts):
    return (160, 120) if opts.quick else (320, 240)


def ensure_meshes():
    if not os.path.exists(os.path.join(ROOT, MESH_SCENE)):
        progress("fetching meshes (scripts/fetch-meshes)")
        r = subprocess.run([os.path.join(ROOT, "scripts", "fetch-meshes")], cwd=ROOT)
        if r.returncode != 0 or not os.path.exists(os.path.join(ROOT, MESH_SCENE)):
            fail("scripts/fetch-meshes did not produce " + MESH_SCENE)


def reference(scene, opts):
    """results/refs/<scene>-<w>x<h>.exr: the scene at 64 subpixels, depth 32, min-weight 0
    (rendered once; kept while its recorded settings match)."""
    if scene == "mesh":
        ensure_meshes()
    w, h = trade_size(opts)
    os.makedirs(os.path.join(RESULTS, "refs"), exist_ok=True)
    path = os.path.join(RESULTS, "refs", "%s-%dx%d.exr" % (scene, w, h))
    settings = json.dumps(TRADE_SCENES[scene] + REFERENCE_SETTINGS)
    stamp = path + ".settings"
    if os.path.exists(path) and os.path.exists(stamp) and open(stamp).read() == settings:
        return path
    progress("rendering reference %s" % os.path.relpath(path, ROOT))
    rt2cpr(TRADE_SCENES[scene] + REFERENCE_SETTINGS +
           ["--width", w, "--height", h, "--output", path], 1)
    with open(stamp, "w") as f:
        f.write(settings)
    return path


def compare_run(scene, extra, opts, frames=None):
    """Renders `scene` at the trade size with `extra` arguments against its reference;
    returns (stats, error dict)."""
    w, h = trade_size(opts)
    ref = reference(scene, opts)
    stats = rt2cpr(TRADE_SCENES[scene] + ["--width", w, "--height", h, "--reference", ref] +
                   extra, frames or opts.frames)
    return stats, stats["reference"]
