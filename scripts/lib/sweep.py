"""The generic parameter sweep behind scripts/sweep-*: fps against one rt2cpr parameter, for
each preset, optionally for several variants (e.g. both BVH splits), with the thesis's curve
overlaid. Both are normalised to their first point: the thesis ran on a 6-core Core i7 in
2011, so absolute fps do not compare, the shapes do.
"""

from rt2exp import (Panel, Results, Series, normalised, plot, preset_args, progress, rt2cpr,
                    measurement)


def parameters(stats):
    """Every parameter of a run, from its --stats JSON."""
    keys = ("scene", "preset", "width", "height", "subpixels", "pattern", "depth", "min_weight",
            "lights", "leaf_size", "split", "backend", "threads", "grain", "kernel")
    return {k: stats[k] for k in keys}


def parameter_sweep(name, title, param, values, to_args, opts, xlabel, thesis=None,
                    variants=(("", []),), logx=False, frames_for=None, extra_columns=None,
                    extra_panels=None):
    """Runs rt2cpr for every preset x variant x value; writes results/<name>.csv/.png.

    to_args(value, preset) -> rt2cpr arguments; variants: (label, extra arguments);
    frames_for(value) -> frames (default opts.frames); extra_columns(stats) -> dict of more
    columns; extra_panels(results) -> more plot panels. Returns the Results."""
    res = Results(name)
    for preset in opts.presets:
        for label, vargs in variants:
            for v in values:
                frames = frames_for(v) if frames_for else opts.frames
                args = preset_args(preset, opts) + ["--threads", opts.threads] + vargs + to_args(v, preset)
                progress("%s: %s %s %s = %s" % (name, preset, label, param, v))
                stats = rt2cpr(args, frames)
                row = dict(parameters(stats))
                row.update({"sweep": param, "value": v, "variant": label})
                row.update(measurement(stats))
                if extra_columns:
                    row.update(extra_columns(stats))
                res.add(**row)
    panels = []
    for preset in opts.presets:
        series = []
        for label, _ in variants:
            pts = [(r["value"], r["fps_median"]) for r in res.select(preset=preset, variant=label)]
            series.append(Series("rt2 " + label if label else "rt2", normalised(pts)))
        if thesis:
            series.append(Series("thesis", normalised(thesis[preset]), dashed=True))
        panels.append(Panel(preset, xlabel, "fps / fps at %s = %s" % (param, values[0]), series,
                            logx=logx))
    if extra_panels:
        panels += extra_panels(res)
    plot(name, title, panels)
    return res
