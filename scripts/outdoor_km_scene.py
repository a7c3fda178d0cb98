#!/usr/bin/env python3
"""Writes scenes/outdoor_km.yaml: the outdoor park grown to a square kilometre (the
park's ground, materials and robot, a route of about 1.07 km), so the terrain is
paged and drawn by distance; with --tr-long, scenes/tr_long.yaml: visual teach &
repeat over the first 520 m of the same loop. The route is deterministic, so the file
is the same on every run of this script:

    python3 scripts/outdoor_km_scene.py > scenes/outdoor_km.yaml
    python3 scripts/outdoor_km_scene.py --tr-long > scenes/tr_long.yaml

The loop is r(θ) = 160 + 15 sin 5θ m around the origin (five lobes, curvature radius
at least about 60 m), sampled every 2 m of arc. It crosses grass (the default), a
band of dry sand in the east, a paved path in the north and sandy loam in the west;
trees and benches are scattered by density over the loop's surroundings, kept
1.5 m clear of it.
"""
import math
import sys

R0, WIGGLE, LOBES = 160.0, 15.0, 5


def radius(t):
    return R0 + WIGGLE * math.sin(LOBES * t)


def point(t):
    r = radius(t)
    return r * math.cos(t), r * math.sin(t)


def route(step_m=2.0):
    # Resample the closed curve at equal arc length.
    fine = [point(2 * math.pi * k / 20000) for k in range(20000)]
    out, carried = [fine[0]], 0.0
    for a, b in zip(fine, fine[1:] + fine[:1]):
        carried += math.dist(a, b)
        if carried >= step_m:
            out.append(b)
            carried = 0.0
    length = sum(math.dist(a, b) for a, b in zip(fine, fine[1:] + fine[:1]))
    return out, length


def fmt(x):
    return f"{x:.2f}".rstrip("0").rstrip(".")


TR_LONG_M = 520.0  # teach & repeat: 520 m of the loop …
TR_START_DEG = 20.0  # … from this polar angle, counter-clockwise
TR_TEACH_SPEED, TR_REPEAT_SPEED = 0.2, 0.1  # [m/s], as scenes/tr_outdoor.yaml


def header(length, speed, tr_long):
    if not tr_long:
        return [
            "# The outdoor park grown to a square kilometre (docs/rendering.md): "
            "the park's rough grass,",
            "# its materials and robot, over 1 km x 1 km, and a loop of %.0f m that crosses"
            % length,
            "# grass, a band of dry sand, a paved path and sandy loam, with uneven soil. The",
            "# terrain is held in tiles and drawn in detail only near the robot",
            "# (docs/rendering.md). Written by",
            "#   python3 scripts/outdoor_km_scene.py > scenes/outdoor_km.yaml",
            "seed: 1",
            "duration_s: %d" % (math.ceil(length / speed / 10) * 10 + 20),
        ]
    return [
        "# Visual teach & repeat over %.0f m outdoors (docs/teach_repeat.md): half of" % length,
        "# scenes/outdoor_km.yaml's loop, over grass, paving and sandy loam, taught at %s m/s"
        % fmt(speed),
        "# and repeated from the images at %s m/s. The teach map's key images stay on disk"
        % fmt(TR_REPEAT_SPEED),
        "# and are read as the repeat reaches them (docs/teach_repeat.md). Written by",
        "#   python3 scripts/outdoor_km_scene.py --tr-long > scenes/tr_long.yaml",
        "#   trackbed run scenes/tr_long.yaml --out runs/tr_long --set teach_repeat.method=3d",
        "seed: 1",
        "duration_s: %d" % (math.ceil(length / TR_REPEAT_SPEED / 10) * 10 + 100),
    ]


def main():
    tr_long = "--tr-long" in sys.argv[1:]
    waypoints, length = route()
    if tr_long:
        # The open route along the loop from TR_START_DEG, past the band of dry sand
        # (too few features there to repeat from:
        # docs/results/2026-12-06-long-routes.md), up to TR_LONG_M of path.
        start = min(range(len(waypoints)), key=lambda k: abs(
            math.atan2(waypoints[k][1], waypoints[k][0]) - math.radians(TR_START_DEG)))
        waypoints = waypoints[start:] + waypoints[:start]
        kept, along = waypoints[:1], 0.0
        for a, b in zip(waypoints, waypoints[1:]):
            along += math.dist(a, b)
            kept.append(b)
            if along >= TR_LONG_M:
                break
        waypoints, length = kept, along
    x0, y0 = waypoints[0]
    x1, y1 = waypoints[1]
    yaw = math.degrees(math.atan2(y1 - y0, x1 - x0))
    speed = TR_TEACH_SPEED if tr_long else 0.4
    lines = header(length, speed, tr_long) + [
        "scene:",
        "  name: %s" % ("tr_long" if tr_long else "outdoor_km"),
        "  terrain:",
        "    extent_m: [-500, -500, 500, 500]",
        "    cell_size_m: 0.1",
        "    # The park's roughness (scenes/outdoor.yaml).",
        "    roughness:",
        "      undulation_amplitude_m: 0.25",
        "      undulation_wavelength_m: 7.0",
        "      bump_amplitude_m: 0.03",
        "      bump_wavelength_m: 0.7",
        "    default_material: grass",
        "    regions:",
        "      - {material: dry_sand, shape: rectangle, min: [120, -45], max: [200, 40]}",
        "      - {material: paving, shape: rectangle, min: [-70, 140], max: [70, 190]}",
        "      - {material: sandy_loam, shape: circle, center: [-165, 10], radius_m: 35}",
        "      - {material: clay, shape: circle, center: [40, -175], radius_m: 12}",
        "    # Uneven soil as scenes/sweeps/soil_variation.yaml (docs/physics.md).",
        "    soil_variation: {amplitude: 0.3, correlation_length_m: 2}",
        "  appearance:",
        "    terrain_full_detail_m: 2",
    ] + ([] if tr_long else [
        # The park's target is speed; tr_long's repeats are measured on full detail.
        "    # Far trees with fewer facets where their outline moves by under half a",
        "    # pixel (docs/rendering.md).",
        "    object_far_error_px: 0.5",
    ]) + [
        "  scatter:",
        "    - {type: tree, density_per_100m2: 0.4, region_m: [-200, -200, 200, 200],",
        "       radius_m: [0.15, 0.35], height_m: [3, 7], materials: [grass, sandy_loam],",
        "       clearance_m: 1.5}",
        "    - {type: bench, density_per_100m2: 0.02, region_m: [-200, -200, 200, 200],",
        "       size_m: [1.5, 0.45], height_m: [0.45, 0.45], clearance_m: 1.5}",
        "robot:",
        "  start: {x_m: %s, y_m: %s, yaw_deg: %s}" % (fmt(x0), fmt(y0), fmt(yaw)),
        "  stereo: {enabled: true}",
        "drive:",
        "  mode: path",
    ] + ([] if tr_long else ["  closed: true"]) + [
        "  speed_mps: %s" % fmt(speed),
        "  lookahead_m: 0.6",
    ]
    pts = ", ".join("[%s, %s]" % (fmt(x), fmt(y)) for x, y in waypoints)
    # Wrapped at about 90 columns.
    wrapped, line = [], "  waypoints: ["
    for p in pts.split(", ["):
        piece = p if p.startswith("[") else "[" + p
        if len(line) + len(piece) > 88:
            wrapped.append(line.rstrip())
            line = "              "
        line += piece + ", "
    wrapped.append(line.rstrip(", ") + "]")
    # teach_repeat follows the drive's keys.
    teach_repeat = [
        "teach_repeat:",
        "  enabled: true",
        "  method: 2d",
        "  repeat_speed_mps: %s" % fmt(TR_REPEAT_SPEED),
        "  repeat_turn_rate_deg_s: 8",
    ] if tr_long else []
    print("\n".join(lines + wrapped + teach_repeat))


if __name__ == "__main__":
    main()
