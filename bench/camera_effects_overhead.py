#!/usr/bin/env python3
"""What each image effect of the camera costs in speed (docs/camera_model.md): the outdoor
park on the ideal robot with a pinhole global-shutter camera, and with one effect on at a
time (typical's sensor in electrons; EuRoC's lens; a 68.75 us rolling shutter; a 10 ms
exposure warped at 4 instants; lens and shutter; 2 x 2 samples per pixel, without and
with the lens; the sun's shadows baked into a light map, scene_lighting.h), each run
--repeats times interleaved, by the real-time factor metrics.json reports. A benchmark:
it prints figures and ratios to the plain camera, pair by pair; it never fails on them.

    python3 bench/camera_effects_overhead.py [--duration 30] [--repeats 3]
"""
import argparse
import json
import pathlib
import statistics
import subprocess
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]
LENS = ("robot.stereo.distortion={model: radial_tangential, k1: -0.28340811, "
        "k2: 0.07395907, p1: 0.00019359, p2: 1.76187114e-05}")
SHUTTER = "robot.stereo.rolling_shutter.line_delay_s=6.875e-05"
VARIANTS = {
    "pinhole": [],
    "sensor (IMX174)": ["robot.stereo.photometric.enabled=true"],
    "lens": [LENS],
    "rolling shutter": [SHUTTER],
    "10 ms exposure": ["robot.stereo.exposure_time_s=0.01"],
    "lens + shutter": [LENS, SHUTTER],
    "supersampled 2x": ["robot.stereo.supersampling=2"],
    "lens, 2x": [LENS, "robot.stereo.supersampling=2"],
    "sun's shadows (baked)": ["scene.appearance.lighting={sun_shadows: true}"],
}


def run(trackbed_bin, sets, duration, out):
    command = [str(trackbed_bin), "run", str(ROOT / "scenes/outdoor.yaml"), "--out", str(out),
               "--set", f"duration_s={duration}", "--set", "robot.realism=ideal"]
    for s in sets:
        command += ["--set", s]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    return json.loads((out / "metrics.json").read_text())["real_time_factor"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=30.0)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--trackbed", default=str(ROOT / "build/apps/trackbed"))
    args = parser.parse_args()
    rtf = {name: [] for name in VARIANTS}
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(args.repeats):
            for name, sets in VARIANTS.items():
                out = pathlib.Path(tmp) / f"{name.replace(' ', '_')}_{k}"
                rtf[name].append(run(args.trackbed, sets, args.duration, out))
    for name, values in rtf.items():
        ratios = [v / p for v, p in zip(values, rtf["pinhole"])]
        print(f"{name:16s} real-time factor median {statistics.median(values):6.2f} "
              f"({', '.join(f'{v:.2f}' for v in values)}); / pinhole pair by pair: median "
              f"{statistics.median(ratios):.3f}")


if __name__ == "__main__":
    main()
