#!/usr/bin/python3
"""Optical flow and motion vectors against known motion (tests/data/flow):
on the sliding textured plane and on the sky the forward and backward flow
equal the flow computed analytically from the written camera parameters and
the plane's known step; motion_vectors are the backward flow in Isaac's
layout; the first frame's backward flow and the last frame's forward flow
are zero; and frame t sampled at each pixel of frame t+1 displaced by frame
t+1's backward flow reproduces frame t+1 away from occlusions."""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

from checklib import check, dataset_hashes, failures, finish

PLANE_STEP = np.array([0.05, 0.02, 0.0])  # flow.yaml: /World/Plane's steadyMotion step
FLOW_TOLERANCE_PX = 0.02   # float32 depth read back from GL, recomputed in doubles here
PHOTOMETRIC_MEAN = 3.0     # grey levels: bilinear resampling of a checker texture at 120 x 90 (unwarped: ~7)
CONSISTENT_PX = 0.5        # forward-backward check for pixels seen in both frames


def camera(out, frame):
    p = json.load(open(f"{out}/camera_params_{frame:04d}.json"))
    view = np.array(p["cameraViewTransform"]).reshape(4, 4)   # row-vector layout: x_view = x_world @ view
    proj = np.array(p["cameraProjection"]).reshape(4, 4)
    return view, proj


def project(points_h, view, proj, w, h):
    clip = points_h @ view @ proj
    ndc = clip[..., :2] / clip[..., 3:4]
    return np.stack([(1 - ndc[..., 1]) * 0.5 * h, (ndc[..., 0] + 1) * 0.5 * w], -1)  # (row, col)


def pixel_rays(view, proj, w, h):
    """World origin and direction of each pixel centre's ray."""
    ys, xs = np.mgrid[0:h, 0:w] + 0.5
    ndc = np.stack([xs / w * 2 - 1, 1 - ys / h * 2], -1)
    inverse = np.linalg.inv(view @ proj)
    def unproject(z):
        clip = np.concatenate([ndc, np.full(ndc.shape[:2] + (1,), z), np.ones(ndc.shape[:2] + (1,))], -1)
        world = clip @ inverse
        return world[..., :3] / world[..., 3:4]
    near, far = unproject(0.9), unproject(0.1)
    return near, far - near


def analytic_flow(out, t, other, plane_moves, w, h):
    view, proj = camera(out, t)
    view2, proj2 = camera(out, other)
    origin, direction = pixel_rays(view, proj, w, h)
    pixel = np.stack(np.mgrid[0:h, 0:w] + 0.5, -1)
    # The plane (z = 0) under each pixel, moved with the plane.
    s = -origin[..., 2] / direction[..., 2]
    point = origin + direction * s[..., None] + plane_moves * PLANE_STEP
    plane = project(np.concatenate([point, np.ones((h, w, 1))], -1), view2, proj2, w, h) - pixel
    # The sky: the ray's direction at infinity.
    d = direction / np.linalg.norm(direction, axis=-1, keepdims=True)
    sky = project(np.concatenate([d, np.zeros((h, w, 1))], -1), view2, proj2, w, h) - pixel
    return plane, sky


def bilinear(image, rows, cols):
    h, w = image.shape[:2]
    r = np.clip(rows - 0.5, 0, h - 1.001)
    c = np.clip(cols - 0.5, 0, w - 1.001)
    r0, c0 = np.floor(r).astype(int), np.floor(c).astype(int)
    fr, fc = (r - r0)[..., None], (c - c0)[..., None]
    return ((1 - fr) * (1 - fc) * image[r0, c0] + (1 - fr) * fc * image[r0, c0 + 1]
            + fr * (1 - fc) * image[r0 + 1, c0] + fr * fc * image[r0 + 1, c0 + 1])


def main():
    binary, scene = (os.path.abspath(a) for a in sys.argv[1:3])
    with tempfile.TemporaryDirectory() as out:
        p = subprocess.run([binary, "run", scene, "--out", out], capture_output=True, text=True)
        if p.returncode != 0:
            print(f"run exited {p.returncode}: {p.stderr[-600:]}")
            return 1
        frames = 4
        fw = [np.load(f"{out}/forward_flow_{t:04d}.npy") for t in range(frames)]
        bw = [np.load(f"{out}/backward_flow_{t:04d}.npy") for t in range(frames)]
        mv = [np.load(f"{out}/motion_vectors_{t:04d}.npy") for t in range(frames)]
        rgb = [np.asarray(Image.open(f"{out}/rgb_{t:04d}.png"))[..., :3].astype(np.float64) for t in range(frames)]
        ids = [np.asarray(Image.open(f"{out}/instance_id_segmentation_{t:04d}.png")) for t in range(frames)]
        h, w = rgb[0].shape[:2]
        check(fw[0].shape == (h, w, 2) and fw[0].dtype == np.float32, f"forward_flow {fw[0].shape} {fw[0].dtype}")
        check(mv[0].shape == (h, w, 4) and mv[0].dtype == np.float32, f"motion_vectors {mv[0].shape} {mv[0].dtype}")
        check(not np.any(bw[0]) and not np.any(fw[-1]), "first backward / last forward flow not zero")
        for t in range(frames):
            mapping = json.load(open(f"{out}/instance_id_segmentation_mapping_{t:04d}.json"))
            plane_id = int(next(k for k, v in mapping.items() if v == "/World/Plane"))
            plane, sky = ids[t] == plane_id, ids[t] == 0
            check(plane.sum() > 1000 and sky.sum() > 500, f"frame {t}: plane {plane.sum()} sky {sky.sum()} pixels")
            for other, flow, sign in ((t + 1, fw[t], 1), (t - 1, bw[t], -1)):
                if not 0 <= other < frames:
                    continue
                plane_flow, sky_flow = analytic_flow(out, t, other, sign, w, h)
                for name, mask, expected in (("plane", plane, plane_flow), ("sky", sky, sky_flow)):
                    error = np.abs(flow[mask] - expected[mask]).max()
                    check(error <= FLOW_TOLERANCE_PX,
                          f"frame {t} -> {other}: {name} flow off by {error:.4f} px (e.g. {flow[mask][0]} vs {expected[mask][0]})")
            check(np.array_equal(mv[t][..., 0], bw[t][..., 1]) and np.array_equal(mv[t][..., 1], bw[t][..., 0])
                  and not np.any(mv[t][..., 2:]), f"frame {t}: motion_vectors are not the backward flow (x, y)")
            check(t == frames - 1 or np.abs(fw[t][plane]).max() > 0.5, f"frame {t}: the plane hardly moves")
        # Warping: frame t sampled where frame t+1's backward flow points.
        for t in range(frames - 1):
            rows, cols = np.mgrid[0:h, 0:w] + 0.5
            back = bw[t + 1]
            warped = bilinear(rgb[t], rows + back[..., 0], cols + back[..., 1])
            there_r, there_c = rows + back[..., 0], cols + back[..., 1]
            inside = (there_r > 1) & (there_r < h - 1) & (there_c > 1) & (there_c < w - 1)
            # Seen in both frames: the forward flow there leads back.
            ahead = bilinear(fw[t], there_r, there_c)
            consistent = inside & (np.linalg.norm(ahead + back, axis=-1) < CONSISTENT_PX)
            # Away from the boundaries between surfaces, where the colour mixes.
            edges = np.zeros((h, w), bool)
            i = ids[t + 1]
            edges[1:, :] |= i[1:, :] != i[:-1, :]
            edges[:-1, :] |= i[1:, :] != i[:-1, :]
            edges[:, 1:] |= i[:, 1:] != i[:, :-1]
            edges[:, :-1] |= i[:, 1:] != i[:, :-1]
            keep = consistent & ~edges
            error = np.abs(warped - rgb[t + 1]).mean(axis=-1)[keep]
            check(keep.sum() > 0.6 * h * w, f"frame {t + 1}: only {keep.sum()} pixels to compare")
            check(error.mean() <= PHOTOMETRIC_MEAN, f"frame {t + 1}: warped frame {t} differs by {error.mean():.2f} levels")
            unwarped = np.abs(rgb[t] - rgb[t + 1]).mean(axis=-1)[keep]
            check(error.mean() < 0.5 * unwarped.mean(), f"frame {t + 1}: warping hardly helps ({error.mean():.2f} vs "
                                                         f"{unwarped.mean():.2f} levels unwarped)")
            occluded = inside & ~consistent
            check(occluded.sum() > 0, f"frame {t + 1}: no occluded pixels found (the box should hide some)")
        # Each iteration is its own sequence; shards (which step one frame past
        # their last) add up to the whole run, whatever the thread count.
        runs = {}
        for name, flags in (("whole", ["--threads", "1"]), ("shards", None)):
            target = f"{out}/{name}"
            if flags is not None:
                subprocess.run([binary, "run", scene, "--out", target, "--iterations", "2", *flags], capture_output=True)
            else:
                for i in range(3):
                    subprocess.run([binary, "run", scene, "--out", target, "--iterations", "2", "--shard", f"{i}/3",
                                    "--threads", "2"], capture_output=True)
                subprocess.run([binary, "merge", target], capture_output=True)
            runs[name] = dataset_hashes(target)
        check(len(runs["whole"]) > 40 and runs["whole"] == runs["shards"], "3 shards merged differ from the whole run")
        check(not np.any(np.load(f"{out}/whole/backward_flow_0004.npy")) and np.any(np.load(f"{out}/whole/backward_flow_0005.npy"))
              and not np.any(np.load(f"{out}/whole/forward_flow_0003.npy")),
              "the second iteration's first frame has a backward flow, or the first's last a forward flow")
        return finish("ok: flow matches the analytic motion; warped frames match; shards add up")


if __name__ == "__main__":
    sys.exit(main())
