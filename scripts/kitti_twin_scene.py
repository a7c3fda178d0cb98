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

The street's clutter (docs/rendering.md, "Facades" and "Parked cars"): parked cars of
type `car`, drawn from parts, each facing the way its side's traffic goes (the right
side's along +x); house fronts with the `facade` texture (storeys and windows), a door
of DIN 18101's 1.0 x 2.125 m opening on each, at a pier between two windows, and a DN 100
downpipe (DIN EN 612) at each front corner. `--cars boxes --houses plain` writes the
street as it was before them: plain boxes of metal or paint, houses of brick or paint
(the layout drawn from the seed is the same either way).

Leafy crowns and street furniture (docs/rendering.md, "Leafy crowns" and "Street
furniture"): the trees' crowns drawn as leaf cards (`scene.appearance.crowns: leaves`);
kerbstones of DIN 483's H 15 x 30 (1 m long, 0.15 m wide) along both carriageway edges,
showing 0.12 m above the road (RASt 06's 10-12 cm); street lamps of 6 m at the rear of
the right footway every 25-35 m (a residential road's mounting height and spacing under
EN 13201); sign posts of 60.3 mm tube with a 0.6 m square sign (VwV-StVO's size 2) whose
lower edge is 2.0 m up and whose edge is 0.5 m from the carriageway (VwV-StVO). Their
layout is drawn from a stream of its own, so the street's layout is unchanged.
`--crowns spheres --furniture off` writes the street without them.
"""
import argparse
import random

ROAD_START, ROAD_END = -30.0, 640.0


CARRIAGEWAY_EDGE = 4.0  # |y| of the asphalt's edge
FOOTWAY_BACK = 9.0  # |y| of the pavement's back edge
KERB_LENGTH, KERB_WIDTH, KERB_REVEAL, KERB_JOINT = 1.0, 0.15, 0.12, 0.005
LAMP_HEIGHT, LAMP_RADIUS = 6.0, 0.07
SIGN_SIDE, SIGN_LOWER_EDGE, SIGN_CLEARANCE, SIGN_POST_RADIUS = 0.6, 2.0, 0.5, 0.03015

DOOR_WIDTH, DOOR_HEIGHT, DOOR_DEPTH = 1.0, 2.125, 0.05
PIPE_RADIUS = 0.05
BAY = 3.0  # the facade texture's bay (render/facade_texture.h)


def fmt(x, digits=2):
    return f"{x:.{digits}f}".rstrip("0").rstrip(".")


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


def car_line(x, y, length, width, height, look, parts):
    if not parts:
        return (f"    - {{type: box, center: [{fmt(x)}, {fmt(y)}], size_m: [{fmt(length)}, "
                f"{fmt(width)}, {fmt(height)}], appearance: {look}}}")
    yaw = 0 if y < 0 else 180  # facing the way the traffic on its side goes
    return (f"    - {{type: car, center: [{fmt(x)}, {fmt(y)}], size_m: [{fmt(length)}, "
            f"{fmt(width)}, {fmt(height)}], yaw_deg: {yaw}, appearance: {look}}}")


def house_front(x, y, length, depth, height, rng):
    """A door at a pier between two windows and a downpipe at each front corner of the
    house at (x, y), as scene lines."""
    side = 1 if y > 0 else -1
    front = abs(y) - depth / 2  # the face towards the road, |y|
    bays = int(length / BAY)
    out = []
    if bays >= 2:
        # The facade's bays start at the face's corner where its texture does
        # (render/gl_primitives.cpp's DrawBox): the +x end on the right side.
        k = rng.randint(1, bays - 1)
        door_x = x + length / 2 - k * BAY if side < 0 else x - length / 2 + k * BAY
        door_y = side * (front - DOOR_DEPTH / 2)
        out.append(f"    - {{type: door, center: [{fmt(door_x, 3)}, {fmt(door_y, 3)}], "
                   f"size_m: [{fmt(DOOR_WIDTH)}, {fmt(DOOR_DEPTH)}, {fmt(DOOR_HEIGHT, 3)}]}}")
    for end in (-1, 1):
        out.append(f"    - {{type: post, center: [{fmt(x + end * (length / 2 - 0.15))}, "
                   f"{fmt(side * (front - 0.08))}], radius_m: {fmt(PIPE_RADIUS)}, "
                   f"height_m: {fmt(height)}}}")
    return out


def kerbs():
    """Kerbstones along both carriageway edges, a joint between each two, as scene lines."""
    out = []
    for side in (-1, 1):
        y = side * (CARRIAGEWAY_EDGE + KERB_WIDTH / 2)
        x = -40.0
        while x + KERB_LENGTH <= 650.0:
            out.append(f"    - {{type: box, center: [{fmt(x + KERB_LENGTH / 2, 3)}, {fmt(y, 3)}], "
                       f"size_m: [{fmt(KERB_LENGTH - KERB_JOINT, 3)}, {fmt(KERB_WIDTH)}, "
                       f"{fmt(KERB_REVEAL)}], appearance: paving}}")
            x += KERB_LENGTH
    return out


def clear_of(x, taken, gap):
    return all(abs(x - t) >= gap for t in taken)


def lamps_and_signs(rng, tree_xs):
    """Street lamps at the rear of the right footway and sign posts by both kerbs, clear of
    the trees along the street, as scene lines."""
    out = []
    x = ROAD_START + rng.uniform(0, 10)
    while x < ROAD_END:
        y = -(FOOTWAY_BACK - 0.5)
        out.append(f"    - {{type: post, center: [{fmt(x)}, {fmt(y)}], "
                   f"radius_m: {fmt(LAMP_RADIUS)}, height_m: {fmt(LAMP_HEIGHT)}}}")
        # The lantern: 0.6 x 0.25 x 0.12 m on top, reaching 0.3 m over the footway.
        out.append(f"    - {{type: box, center: [{fmt(x)}, {fmt(y + 0.3)}], "
                   f"size_m: [0.25, 0.6, 0.12], base_z_m: {fmt(LAMP_HEIGHT - 0.12)}, "
                   f"collides: false, appearance: metal}}")
        x += rng.uniform(25, 35)
    for side in (-1, 1):
        x = ROAD_START + rng.uniform(0, 30)
        while x < ROAD_END:
            if clear_of(x, tree_xs[side], 1.0):
                y = side * (CARRIAGEWAY_EDGE + SIGN_CLEARANCE + SIGN_SIDE / 2)
                out.append(f"    - {{type: post, center: [{fmt(x)}, {fmt(y)}], "
                           f"radius_m: {fmt(SIGN_POST_RADIUS, 5)}, "
                           f"height_m: {fmt(SIGN_LOWER_EDGE + SIGN_SIDE)}}}")
                # The sign faces the traffic on its side, just before the post.
                out.append(f"    - {{type: box, center: [{fmt(x - side * 0.045, 3)}, {fmt(y)}], "
                           f"size_m: [0.02, {fmt(SIGN_SIDE)}, {fmt(SIGN_SIDE)}], "
                           f"base_z_m: {fmt(SIGN_LOWER_EDGE)}, collides: false, "
                           f"appearance: plain_paint}}")
            x += rng.uniform(40, 90)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cars", choices=["parts", "boxes"], default="parts")
    parser.add_argument("--houses", choices=["facades", "plain"], default="facades")
    parser.add_argument("--crowns", choices=["leaves", "spheres"], default="leaves")
    parser.add_argument("--furniture", choices=["on", "off"], default="on")
    args = parser.parse_args()
    rng = random.Random(20121001)
    dressing = random.Random(20121002)  # doors: their own stream, the layout unchanged
    furniture = random.Random(20121003)  # lamps and signs: theirs
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
    ground_look: detailed""" + ("""
    # The trees' crowns as leaf cards (docs/rendering.md, "Leafy crowns").
    crowns: leaves""" if args.crowns == "leaves" else "") + """
  objects:""")
    for x, y, length, width, height, look in cars(rng):
        print(car_line(x, y, length, width, height, look, args.cars == "parts"))
    tree_list = trees(rng)
    for x, y, r, h in tree_list:
        print(f"    - {{type: tree, center: [{fmt(x)}, {fmt(y)}], radius_m: {fmt(r)}, "
              f"height_m: {fmt(h)}}}")
    for x, y, length, depth, height, look in houses(rng):
        if args.houses == "facades":
            look = "facade"
        print(f"    - {{type: box, center: [{fmt(x)}, {fmt(y)}], size_m: [{fmt(length)}, "
              f"{fmt(depth)}, {fmt(height)}], appearance: {look}}}")
        if args.houses == "facades":
            print("\n".join(house_front(x, y, length, depth, height, dressing)))
    if args.furniture == "on":
        print("\n".join(kerbs()))
        tree_xs = {side: [t[0] for t in tree_list if t[1] * side > 0] for side in (-1, 1)}
        print("\n".join(lamps_and_signs(furniture, tree_xs)))
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
