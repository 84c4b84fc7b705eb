#!/usr/bin/python3
"""Compares renders against a reference in linear radiance.

    tools/cycles/compare.py --reference cycles_1024.npy \\
        rasterizer=out/rgb_0000.png cycles_32=cycles_32.npy pt_64=pt/64/hdr_color_0000.npy \\
        --json report.json --side-by-side side_by_side.png

A candidate is NAME=PATH (or PATH; the name is then the file's stem):
- a .npy of linear radiance, H x W x 3 (or x 4: alpha is dropped), float:
  what Cycles (cycles_render.py) and the path tracer write;
- a .png from sdgbehave's rasterizer (rgb_XXXX.png). Its colour is tone
  mapped (display = 1 - exp(-radiance * exposureScale), then sRGB;
  docs/rendering.md, RenderSettings::exposureScale), so it is inverted back
  to radiance. A saturated channel (255) only says "at least" the radiance
  of 254.5 and is taken as that: those pixels clip, and the table says how
  many there are.
The samples and the time per frame come from NAME.json next to a .npy
(cycles_render.py writes one), else from run_summary.json in the
candidate's folder (sdgbehave: seconds.render / frames_in_run), else they
are left empty.

Metrics, over every pixel and channel:
- rel. MAE = sum |candidate - reference| / sum |reference|;
- block bias = the same over the means of 16 x 16-pixel blocks (whole
  blocks only; every channel): noise averages out in a block, a bias (a
  wrong light level, light a denoiser carried across an edge) does not, so
  it separates a renderer's systematic error from its noise. A render's
  noise alone still leaves some: Cycles at 32 samples against 1,024 scores
  about 0.6 % at 256 x 256 (tools/cycles/README.md, the area-lamp room);
- block bias, exposure fitted = the block bias after the candidate is
  scaled by sum(reference) / sum(candidate), the exposure that matches the
  two means: what is left of the bias when the overall light level is not
  counted (the table's "mean ratio" is that level);
- black where lit = the share of the pixels the reference lights (luminance
  above 1 % of its mean) where the candidate is black (luminance below
  0.1 % of the reference's mean): light the candidate misses entirely,
  such as the rasterizer's shadows without bounce light.

Runs with Debian's /usr/bin/python3 (numpy, PIL).
"""
import argparse
import json
import os
import re
import sys

import numpy as np
from PIL import Image, ImageDraw

EXPOSURE_SCALE = 0.002  # RenderSettings::exposureScale (lib/render/renderer.h)
LUMINANCE = np.array([0.2126, 0.7152, 0.0722], dtype=np.float64)  # Rec. 709, the linear working space


def srgb_to_linear(s):
    return np.where(s <= 0.04045, s / 12.92, ((s + 0.055) / 1.055) ** 2.4)


def linear_to_srgb(m):
    return np.where(m <= 0.0031308, m * 12.92, 1.055 * np.power(np.maximum(m, 0), 1 / 2.4) - 0.055)


def tone_map(radiance, exposure_scale=EXPOSURE_SCALE):
    """Radiance to 8-bit sRGB through sdgbehave's documented tone curve."""
    mapped = 1.0 - np.exp(-np.maximum(radiance, 0) * exposure_scale)
    return np.clip(np.round(linear_to_srgb(mapped) * 255.0), 0, 255).astype(np.uint8)


def png_to_radiance(path, exposure_scale=EXPOSURE_SCALE):
    """The rasterizer's PNG back to radiance; returns (radiance, saturated pixel mask)."""
    rgb = np.asarray(Image.open(path).convert("RGB"), dtype=np.float64)
    saturated = (rgb >= 255).any(axis=2)
    # 255 stands for anything from 254.5 up: take the bottom of that bin.
    level = np.minimum(rgb, 254.5) / 255.0
    mapped = srgb_to_linear(level)
    return -np.log1p(-mapped) / exposure_scale, saturated


def load(path, exposure_scale):
    if path.lower().endswith(".png"):
        return png_to_radiance(path, exposure_scale)
    a = np.load(path).astype(np.float64)
    if a.ndim != 3 or a.shape[2] not in (3, 4):
        sys.exit(f"{path}: expected H x W x 3 linear radiance, got shape {a.shape}")
    return a[:, :, :3], None


def metadata(name, path):
    """Samples, time per frame and whether denoised, from the files beside the candidate."""
    meta = {"samples": None, "seconds_per_frame": None, "seconds_process": None, "denoised": None}
    sidecar = os.path.splitext(path)[0] + ".json"
    summary = os.path.join(os.path.dirname(path), "run_summary.json")
    if path.endswith(".npy") and os.path.exists(sidecar):
        with open(sidecar) as f:
            s = json.load(f)
        meta.update(samples=s.get("samples"), seconds_per_frame=s.get("seconds_render"),
                    seconds_process=s.get("seconds_process"), denoised=s.get("denoised"))
    elif os.path.exists(summary):
        with open(summary) as f:
            s = json.load(f)
        frames = max(int(s.get("frames_in_run") or s.get("frames") or 1), 1)
        seconds = s.get("seconds", {})
        meta["seconds_per_frame"] = seconds.get("render", 0.0) / frames
        meta["seconds_process"] = seconds.get("total")
        # The path tracer's settings, once its run summary carries them.
        settings = s.get("render") if isinstance(s.get("render"), dict) else {}
        meta["samples"] = settings.get("samples")
        meta["denoised"] = settings.get("denoise")
    if meta["denoised"] is None and not path.endswith(".png"):
        meta["denoised"] = "denoised" in name  # compare_with_cycles.sh's pt_N_denoised
    if meta["samples"] is None and not path.endswith(".png"):
        # The last number of the name: pt_256, pt_4_denoised, gpu_h100_1024; a
        # bare hdr_color_0000.npy is named after its folder.
        label = os.path.basename(os.path.dirname(path)) if name.startswith("hdr_color") else name
        numbers = re.findall(r"\d+", label)
        if numbers:
            meta["samples"] = int(numbers[-1])
    return meta


BLOCK = 16


def block_means(image, block=BLOCK):
    """The means of the whole block x block tiles, per channel."""
    h, w = (image.shape[0] // block) * block, (image.shape[1] // block) * block
    tiles = image[:h, :w].reshape(h // block, block, w // block, block, image.shape[2])
    return tiles.mean(axis=(1, 3))


def block_bias(candidate, reference, block=BLOCK):
    a, b = block_means(candidate, block), block_means(reference, block)
    return float(np.abs(a - b).sum() / max(np.abs(b).sum(), 1e-30))


def metrics(candidate, reference, saturated):
    diff = np.abs(candidate - reference)
    lum_ref = reference @ LUMINANCE
    lum_cand = candidate @ LUMINANCE
    mean = max(lum_ref.mean(), 1e-30)
    lit = lum_ref > 0.01 * mean
    black = lum_cand < 0.001 * mean
    out = {"rel_mae": float(diff.sum() / max(np.abs(reference).sum(), 1e-30)),
           "mae": float(diff.mean()),
           "black_where_lit": float((lit & black).sum() / max(lit.sum(), 1)),
           "mean_ratio": float(candidate.mean() / max(reference.mean(), 1e-30)),
           "block_bias": block_bias(candidate, reference)}
    fitted_scale = reference.sum() / max(candidate.sum(), 1e-30)
    out["block_bias_exposure_fitted"] = block_bias(candidate * fitted_scale, reference)
    if saturated is not None:
        keep = ~saturated
        out["saturated"] = float(saturated.mean())
        out["rel_mae_unsaturated"] = float(diff[keep].sum() / max(np.abs(reference[keep]).sum(), 1e-30))
    return out


def label(image, text):
    """A panel with its name in a strip above it."""
    strip = 14
    canvas = Image.new("RGB", (image.width, image.height + strip), (255, 255, 255))
    canvas.paste(image, (0, strip))
    ImageDraw.Draw(canvas).text((3, 1), text, fill=(0, 0, 0))
    return canvas


def side_by_side(path, panels, exposure_scale):
    """Panels (title, radiance or PNG path) tone mapped with sdgbehave's curve, left to right."""
    images = []
    for title, source in panels:
        if isinstance(source, str):
            images.append(label(Image.open(source).convert("RGB"), title))
        else:
            images.append(label(Image.fromarray(tone_map(source, exposure_scale)), title))
    gap = 4
    out = Image.new("RGB", (sum(i.width for i in images) + gap * (len(images) - 1), max(i.height for i in images)),
                    (255, 255, 255))
    x = 0
    for image in images:
        out.paste(image, (x, 0))
        x += image.width + gap
    out.save(path)


def fmt(value, pattern, empty="-"):
    return empty if value is None else pattern.format(value)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    parser.add_argument("candidates", nargs="+", metavar="[NAME=]PATH")
    parser.add_argument("--reference", required=True, help="reference radiance (.npy), e.g. Cycles at 1,024 samples")
    parser.add_argument("--exposure-scale", type=float, default=EXPOSURE_SCALE,
                        help="the rasterizer's tone-curve scale (default 0.002)")
    parser.add_argument("--json", help="write the results here")
    parser.add_argument("--side-by-side", help="write a PNG: ours | Cycles | rasterizer, tone mapped alike")
    parser.add_argument("--ours", help="the candidate shown as 'ours' in the side-by-side (default: the path-traced "
                                       "one with the most samples, if any)")
    args = parser.parse_args()

    reference, _ = load(args.reference, args.exposure_scale)
    ref_meta = metadata(os.path.basename(args.reference), args.reference)
    rows = []
    images = {}
    for spec in args.candidates:
        name, _, path = spec.rpartition("=")
        name = name or os.path.splitext(os.path.basename(path))[0]
        image, saturated = load(path, args.exposure_scale)
        if image.shape != reference.shape:
            sys.exit(f"{path}: shape {image.shape} differs from the reference's {reference.shape}")
        images[name] = (path, image)
        row = {"name": name, "path": os.path.abspath(path), "kind": "rasterizer" if path.endswith(".png") else "radiance"}
        row.update(metadata(name, path))
        row.update(metrics(image, reference, saturated))
        rows.append(row)

    print(f"reference: {args.reference} ({reference.shape[1]}x{reference.shape[0]}, "
          f"{fmt(ref_meta['samples'], '{}')} samples, {fmt(ref_meta['seconds_per_frame'], '{:.2f}')} s)")
    header = (f"{'name':<22} {'samples':>7} {'rel. MAE':>9} {'block bias':>11} {'(fitted)':>9} {'mean ratio':>11} "
              f"{'black where lit':>16} {'s / frame':>10}  note")
    print(header)
    print("-" * len(header))
    for r in rows:
        note = ""
        if "saturated" in r:
            note = (f"{100 * r['saturated']:.1f} % of pixels saturate and clip; "
                    f"rel. MAE without them {100 * r['rel_mae_unsaturated']:.1f} %")
        elif r["denoised"]:
            note = "denoised"
        print(f"{r['name']:<22} {fmt(r['samples'], '{}'):>7} {100 * r['rel_mae']:>8.1f}% "
              f"{100 * r['block_bias']:>10.2f}% {100 * r['block_bias_exposure_fitted']:>8.2f}% "
              f"{r['mean_ratio']:>11.4f} {100 * r['black_where_lit']:>15.1f}% "
              f"{fmt(r['seconds_per_frame'], '{:.3f}'):>10}  {note}")

    if args.json:
        with open(args.json, "w") as f:
            json.dump({"reference": {"path": os.path.abspath(args.reference), **ref_meta},
                       "exposure_scale": args.exposure_scale, "candidates": rows}, f, indent=2)
    if args.side_by_side:
        raster = next((n for n, (p, _) in images.items() if p.endswith(".png")), None)
        ours = args.ours
        if ours is None:
            traced = [r for r in rows if r["kind"] == "radiance" and not r["name"].startswith("cycles")]
            if traced:
                ours = max(traced, key=lambda r: (r["samples"] or 0, bool(r["denoised"])))["name"]
        panels = []
        if ours:
            panels.append((f"ours: {ours}", images[ours][1]))
        panels.append((f"Cycles {fmt(ref_meta['samples'], '{}', '')}".strip(), reference))
        if raster:
            panels.append(("rasterizer", images[raster][0]))
        side_by_side(args.side_by_side, panels, args.exposure_scale)


if __name__ == "__main__":
    main()
