#!/usr/bin/env python3
"""Do the testbed's verdicts transfer? Runs the stereo VO in every configuration of a
study file on the KITTI twin's images and on real KITTI 06, and compares how the two
rank the configurations with `trackbed transfer` (docs/transfer.md).

    python3 scripts/vo_transfer_study.py --out runs/transfer \\
        [--configs scenes/studies/vo_transfer.yaml] [--real ../shared/data/kitti06] \\
        [--twin DIR | --render-with build/apps/trackbed] [--trackbed build/apps/trackbed] \\
        [--jobs 2]

The twin's images: --twin DIR takes a folder of already rendered runs (DIR/seed<N>/images,
as `trackbed run` writes them); otherwise they are rendered into OUT/twin with the
binary --render-with (default: --trackbed): scenes/kitti_twin.yaml with sequence 06's
camera (the four --set flags in the scene's header), 12 m/s, 5 s (51 frames, as
../shared/data/kitti06 has), `robot.realism: typical`, seeds 1-5. Rendering does not
depend on the VO, so one rendering serves every configuration.

Writes OUT/sim/<config>/seed<N>/ and OUT/real/<config>/ (`trackbed vo` outputs), then
OUT/transfer_translation/ and OUT/transfer_rotation/ (`trackbed transfer` on the
frame-to-frame translation and rotation errors). Resumable: a `trackbed vo` output with
its vo_metrics.json is not run again. Needs python3-yaml.
"""
import argparse
import concurrent.futures
import os
import subprocess
import sys

import yaml

SEEDS = [1, 2, 3, 4, 5]
CAMERA_06 = [
    "robot.stereo.width_px=1226",
    "robot.stereo.height_px=370",
    "robot.stereo.focal_length_px=707.0912",
    "robot.stereo.principal_point_px=[601.8873,183.1104]",
]
TWIN = CAMERA_06 + [
    "drive.speed_mps=12",
    "duration_s=5",
    "robot.realism=typical",
    "outputs.save_images=kitti",
]


def flatten(settings, prefix=""):
    """A configuration's nested map of VO keys as dotted KEY=VALUE strings."""
    out = []
    for key, value in settings.items():
        dotted = f"{prefix}{key}"
        if isinstance(value, dict):
            out += flatten(value, dotted + ".")
        elif isinstance(value, bool):
            out.append(f"{dotted}={'true' if value else 'false'}")
        else:
            out.append(f"{dotted}={value!r}" if isinstance(value, float) else f"{dotted}={value}")
    return out


def run(command, log):
    with open(log, "w") as f:
        done = subprocess.run(["nice", "-n", "10"] + command, stdout=f, stderr=subprocess.STDOUT)
    if done.returncode != 0:
        sys.exit(f"vo_transfer_study: failed ({done.returncode}): {' '.join(command)}; see {log}")


def render(binary, out, repo):
    for seed in SEEDS:
        folder = os.path.join(out, f"seed{seed}")
        if os.path.exists(os.path.join(folder, "images", "poses.txt")):
            continue
        command = [binary, "run", os.path.join(repo, "scenes", "kitti_twin.yaml"),
                   "--seed", str(seed), "--out", folder]
        for s in TWIN:
            command += ["--set", s]
        os.makedirs(out, exist_ok=True)
        run(command, folder + ".log")


def vo_jobs(args, configs, twin):
    jobs = []
    for name, settings in configs.items():
        sets = []
        for s in flatten(settings or {}):
            sets += ["--set", s]
        outputs = [(os.path.join(twin, f"seed{seed}", "images"),
                    os.path.join(args.out, "sim", name, f"seed{seed}")) for seed in SEEDS]
        outputs.append((args.real, os.path.join(args.out, "real", name)))
        for images, out in outputs:
            if os.path.exists(os.path.join(out, "vo_metrics.json")):
                continue
            os.makedirs(out, exist_ok=True)
            jobs.append(([args.trackbed, "vo", images, "--out", out] + sets,
                         os.path.join(out, "vo.log")))
    return jobs


def main():
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--out", required=True)
    p.add_argument("--configs", default=os.path.join(repo, "scenes", "studies", "vo_transfer.yaml"))
    p.add_argument("--real", default=os.path.join(repo, "..", "shared", "data", "kitti06"))
    p.add_argument("--twin", help="rendered runs: DIR/seed<N>/images")
    p.add_argument("--trackbed", default=os.path.join(repo, "build", "apps", "trackbed"))
    p.add_argument("--render-with", help="the binary that renders the twin (default --trackbed)")
    p.add_argument("--jobs", type=int, default=2)
    args = p.parse_args()
    with open(args.configs) as f:
        configs = yaml.safe_load(f)["configurations"]
    twin = args.twin
    if not twin:
        twin = os.path.join(args.out, "twin")
        render(args.render_with or args.trackbed, twin, repo)
    jobs = vo_jobs(args, configs, twin)
    print(f"vo_transfer_study: {len(configs)} configurations, {len(jobs)} VO runs to do")
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for future in [pool.submit(run, command, log) for command, log in jobs]:
            future.result()
    for metric, folder in (("translation_error_pct", "transfer_translation"),
                           ("rotation_error_deg", "transfer_rotation")):
        out = os.path.join(args.out, folder)
        command = [args.trackbed, "transfer", "--real", os.path.join(args.out, "real"),
                   "--sim", os.path.join(args.out, "sim"), "--metric", metric, "--out", out]
        print("$ " + " ".join(command), flush=True)
        subprocess.run(command, check=True)


if __name__ == "__main__":
    main()
