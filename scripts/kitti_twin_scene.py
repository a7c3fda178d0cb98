#!/usr/bin/env python3
"""Writes scenes/kitti_twin.yaml: a straight residential street of 670 m (Geiger et al.
2012: KITTI's sequences are residential streets and roads), of which KITTI's car drives
450 m (the street goes on 190 m beyond, so the view ahead never runs out), seen through
KITTI's stereo geometry. The layout is drawn from a fixed seed, so the
file is the same on every run of this script:

    python3 scripts/kitti_twin_scene.py > scenes/kitti_twin.yaml

Measures (metres) are those of a suburban street: an 8 m carriageway with a parking
lane on each side, 2 m verges with trees, 2 m pavements, house fronts 12-20 m from the
centreline.
"""
import random

ROAD_START, ROAD_END = -30.0, 640.0


def fmt(x):
    return f"{x:.2f}".rstrip("0").rstrip(".")


def cars(rng):
    out = []
    for side in (-1, 1):
        x = ROAD_START + rng.uniform(0, 10)
        while x < ROAD_END - 5:
            if rng.random() < 0.6:  # a parked car; else a gap
                length = rng.uniform(3.8, 4.8)
                out.append((x + length / 2, side * 3.1, length, rng.uniform(1.7, 1.9),
                            rng.uniform(1.4, 1.6), rng.choice(["metal", "plain_paint"])))
                x += length + rng.uniform(0.8, 2.5)
            else:
                x += rng.uniform(5, 15)
    return out


def trees(rng):
    out = []
    for side in (-1, 1):
        x = ROAD_START + rng.uniform(0, 8)
        while x < ROAD_END:
            out.append((x, side * rng.uniform(5.6, 6.4), rng.uniform(0.2, 0.35),
                        rng.uniform(6, 10)))
            x += rng.uniform(9, 20)
    return out


def houses(rng):
    out = []
    for side in (-1, 1):
        x = ROAD_START + rng.uniform(0, 6)
        while x < ROAD_END - 8:
            length = rng.uniform(9, 22)
            depth = rng.uniform(8, 12)
            setback = rng.uniform(12, 20)
            out.append((x + length / 2, side * (setback + depth / 2), length, depth,
                        rng.uniform(5, 11), rng.choice(["brick", "plain_paint", "brick"])))
            x += length + rng.uniform(3, 12)
    return out


def main():
    rng = random.Random(20121001)
    print("""# The KITTI twin (docs/localization.md): 450 m of a straight residential road (it goes
# on 190 m beyond, so the view ahead never runs out) as KITTI's car drives it, seen
# through KITTI's stereo geometry. Written by
#   python3 scripts/kitti_twin_scene.py > scenes/kitti_twin.yaml
# which says where the layout's measures come from.
#
# The camera: sequences 00-02's rectified calibration (calib.txt: fx = fy = 718.856 px,
# cx 607.1928, cy 185.2157, 1241 x 376, P1's baseline 386.1448 / 718.856 = 0.53716 m),
# 10 Hz, 1.65 m above the road, level (Geiger et al. 2013, Fig. 3). Sequence 06's
# camera instead:
#   --set robot.stereo.width_px=1226 --set robot.stereo.height_px=370
#   --set robot.stereo.focal_length_px=707.0912
#   --set robot.stereo.principal_point_px=[601.8873,183.1104]
# The car is carried along the lane (drive.mode: pose_path), no vehicle physics: set
# the speed with --set drive.speed_mps=V (5 to 25 m/s). The run saves the images in
# KITTI's layout (images/), on which `trackbed vo` runs as on real data.
seed: 1
duration_s: 100
scene:
  name: kitti_twin
  terrain:
    extent_m: [-40, -40, 650, 40]
    # A flat road: coarse cells, the textures carry the detail. The carriageway is
    # asphalt, the pavements concrete paving.
    cell_size_m: 0.5
    default_material: grass
    regions:
      - {material: asphalt, shape: rectangle, min: [-40, -4], max: [650, 4]}
      - {material: paving, shape: rectangle, min: [-40, 7], max: [650, 9]}
      - {material: paving, shape: rectangle, min: [-40, -9], max: [650, -7]}
  appearance:
    # Every ground material varied tile by tile (no period), asphalt's variants
    # (docs/rendering.md).
    ground_look: detailed
  objects:""")
    for x, y, length, width, height, look in cars(rng):
        print(f"    - {{type: box, center: [{fmt(x)}, {fmt(y)}], size_m: [{fmt(length)}, "
              f"{fmt(width)}, {fmt(height)}], appearance: {look}}}")
    for x, y, r, h in trees(rng):
        print(f"    - {{type: tree, center: [{fmt(x)}, {fmt(y)}], radius_m: {fmt(r)}, "
              f"height_m: {fmt(h)}}}")
    for x, y, length, depth, height, look in houses(rng):
        print(f"    - {{type: box, center: [{fmt(x)}, {fmt(y)}], size_m: [{fmt(length)}, "
              f"{fmt(depth)}, {fmt(height)}], appearance: {look}}}")
    print("""robot:
  vehicle:
    # The carrier's footprint: a car's wheelbase and track (its pitch and roll follow
    # the road over them).
    track_contact_length_m: 2.7
    track_gauge_m: 1.6
  stereo:
    enabled: true
    width_px: 1241
    height_px: 376
    focal_length_px: 718.856
    principal_point_px: [607.1928, 185.2157]
    baseline_m: 0.53716
    # 1.65 m above the road: the body's origin rides com_height_m (0.2 m) above it.
    mount_m: [0, 0, 1.45]
    pitch_down_deg: 0
    rate_hz: 10
    far_m: 250
drive:
  mode: pose_path
  speed_mps: 10
  # Along the right lane, a lane change to the left one at 150-200 m.
  waypoints: [[0, -1.75], [150, -1.75], [200, 1.75], [450, 1.75]]
estimation:
  # The carrier's virtual tracks turn without skidding: no ICR expansion.
  icr_expansion: 1
  # A car's bounds (StereoVisualOdometryOptions::KittiCar()), not the tracked robot's.
  vo:
    max_translation_per_frame_m: 3
    max_rotation_per_frame_deg: 30
    max_acceleration_mps2: 30
outputs:
  save_images: kitti""")


if __name__ == "__main__":
    main()
