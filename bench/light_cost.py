#!/usr/bin/env python3
"""What the robot's shadow, the sky and leafy crowns cost (docs/camera_model.md,
docs/rendering.md): the same short run of a scene with each element off and on, in turn,
--repeats times, by the CPU time of the whole `trackbed run` process (user + system,
every thread: less disturbed than the wall time by other jobs on the machine). A
benchmark: it prints the figures and the ratios to the plain run, pair by pair; it never
fails on them.

    python3 bench/light_cost.py [--scene scenes/studies/robot_shadow.yaml] [--duration 10]
        [--repeats 3]
"""
import argparse
import os
import pathlib
import statistics
import subprocess
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]
PLAIN = ["scene.appearance.robot_shadow=false", "scene.appearance.sky=flat",
         "scene.appearance.crowns=spheres"]
VARIANTS = {
    "plain": PLAIN,
    "robot shadow": PLAIN[1:] + ["scene.appearance.robot_shadow=true"],
    "clear sky": [PLAIN[0], PLAIN[2], "scene.appearance.sky=clear"],
    "cloudy sky": [PLAIN[0], PLAIN[2], "scene.appearance.sky=cloudy"],
    "leafy crowns": PLAIN[:2] + ["scene.appearance.crowns=leaves"],
}


def cpu_seconds(command):
    before = os.times()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    after = os.times()
    return (after.children_user - before.children_user) + (after.children_system -
                                                           before.children_system)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default=str(ROOT / "scenes/studies/robot_shadow.yaml"))
    parser.add_argument("--duration", type=float, default=10.0)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--trackbed", default=str(ROOT / "build/apps/trackbed"))
    args = parser.parse_args()
    cpu = {name: [] for name in VARIANTS}
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(args.repeats):
            for name, sets in VARIANTS.items():
                command = [args.trackbed, "run", args.scene, "--out",
                           str(pathlib.Path(tmp) / f"{name.replace(' ', '_')}_{k}"),
                           "--progress", "none", "--set", f"duration_s={args.duration}",
                           "--set", "outputs.mcap=false"]
                for s in sets:
                    command += ["--set", s]
                cpu[name].append(cpu_seconds(command))
    for name, values in cpu.items():
        ratios = [v / p for v, p in zip(values, cpu["plain"])]
        print(f"{name:13s} CPU {statistics.median(values):6.2f} s "
              f"({', '.join(f'{v:.2f}' for v in values)}); / plain pair by pair: median "
              f"{statistics.median(ratios):.3f} ({', '.join(f'{r:.3f}' for r in ratios)})")


if __name__ == "__main__":
    main()
