#!/usr/bin/env python3
"""A user's own stack in trackbed's loop, from Python: a proportional controller on
ground truth follows the outdoor scene's loop, and an estimator of its own (encoder
distance and gyro heading: dead reckoning) is reported and scored beside the
built-in ones.

    PYTHONPATH=build/python python3 python/tests/drive_outdoor.py OUT [--seed N] [--duration S]
"""
import argparse
import math
import os
import pathlib

import numpy as np

import trackbed

SOURCE_DIR = pathlib.Path(os.environ.get("TRACKBED_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))
SPEED_MPS = 0.4
HEADING_GAIN = 2.0  # yaw rate per radian of heading error [1/s]


def yaw_of(T):
    return math.atan2(T[1, 0], T[0, 0])


def pose(x, y, yaw):
    T = np.eye(4)
    T[0, 0], T[0, 1], T[1, 0], T[1, 1] = math.cos(yaw), -math.sin(yaw), math.sin(yaw), math.cos(yaw)
    T[0, 3], T[1, 3] = x, y
    return T


class DeadReckoning:
    """Encoder distance along a heading integrated from the gyro's z rate."""

    def __init__(self, scenario):
        robot = scenario["robot"]
        start = robot["start"]
        self.x, self.y = start["x_m"], start["y_m"]
        self.yaw = math.radians(start["yaw_deg"])
        self.m_per_tick = (2 * math.pi * robot["vehicle"]["sprocket_radius_m"]
                           / robot["encoders"]["ticks_per_rev"])
        self.ticks = None
        self.imu_t = None

    def update(self, obs):
        for t, gz in obs.imu[:, [0, 3]]:
            if self.imu_t is not None:
                self.yaw += gz * (t - self.imu_t)
            self.imu_t = t
        if obs.encoders is None:
            return
        if self.ticks is not None:
            d = self.m_per_tick * 0.5 * float(np.sum(obs.encoders - self.ticks))
            self.x += d * math.cos(self.yaw)
            self.y += d * math.sin(self.yaw)
        self.ticks = obs.encoders.copy()

    def T_world_body(self):
        return pose(self.x, self.y, self.yaw)


def drive(out, seed=1, duration_s=15.0):
    """Runs the outdoor scene for duration_s under the controller; returns the metrics."""
    sim = trackbed.Simulation(SOURCE_DIR / "scenes/outdoor.yaml", seed=seed,
                              overrides={"duration_s": duration_s})
    scenario = sim.scenario
    waypoints = scenario["drive"]["waypoints"]
    half_gauge = 0.5 * scenario["robot"]["vehicle"]["track_gauge_m"]
    mine = DeadReckoning(scenario)
    target, left, right = 1, 0.0, 0.0
    while not sim.done:
        obs = sim.step(left_mps=left, right_mps=right)
        mine.update(obs)
        sim.report_estimate("mine", mine.T_world_body())
        # The controller: heading towards the next waypoint, from ground truth.
        T = obs.ground_truth
        x, y = T[0, 3], T[1, 3]
        while math.hypot(waypoints[target][0] - x, waypoints[target][1] - y) < 0.6:
            target = (target + 1) % len(waypoints)
        wanted = math.atan2(waypoints[target][1] - y, waypoints[target][0] - x)
        error = math.remainder(wanted - yaw_of(T), 2 * math.pi)
        yaw_rate = HEADING_GAIN * error
        left, right = SPEED_MPS - yaw_rate * half_gauge, SPEED_MPS + yaw_rate * half_gauge
    return sim.finish(out=out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--duration", type=float, default=15.0)
    args = parser.parse_args()
    metrics = drive(args.out, args.seed, args.duration)
    for name, e in sorted(metrics["estimators"].items()):
        print(f"{name:22s} ATE {e['ate_rmse_m']:.3f} m, final {e['final_error_m']:.3f} m")


if __name__ == "__main__":
    main()
