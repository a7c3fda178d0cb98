#!/usr/bin/env bash
# The image-statistics tables of docs/image_statistics.md, rendered by a given binary:
# real KITTI 06 against the KITTI twin (sequence 06's camera) and the robot's scenes
# (corridor, park, the kilometre park's sand), per band of rows.
#
#   bash scripts/image_statistics_table.sh BIN OUTDIR [STATS_BIN]
#
#   BIN        the `trackbed` binary whose renderer draws the images (e.g. a pinned
#              build of the commit before a renderer change, then build/apps/trackbed
#              after it).
#   OUTDIR     where everything goes (created): runs/NAME/ the run folders with their
#              images, stats/*.json|csv what `image-stats` wrote, vo/NAME/ `trackbed
#              vo` on the twin's renders and on KITTI 06, stereo/NAME.png one stereo
#              pair per robot scene (left | right, scripts/stereo_pair_png.py), and
#              tables.md, the tables as Markdown.
#   STATS_BIN  the `trackbed` binary that measures (`image-stats`, `vo`); default:
#              build/apps/trackbed of this checkout. Keep it the same for "before" and
#              "after" so that only the renderer differs.
#
# Environment: TRACKBED_DATA_DIR, the real-data folder (default: the build's CMake
# setting of that name, else ../shared/data beside the checkout); KITTI 06's frames
# 0–50 are read from its kitti06/. NICE (default 10), the niceness runs get.
#
# Resumable: a run whose folder has metrics.json and whose BIN has the same SHA-256 as
# recorded in runs/NAME.bin is not rendered again; a run by another binary is rendered
# anew. The measurements are always taken again (a few minutes). Renders run one at a
# time under `nice`; on a loaded 2-core machine the whole set takes about 15 minutes
# (the four twin renders about 3, corridor and park about 2–3 each, the sand 1,
# the measurements about 5).
#
# What is rendered (seed 1 everywhere):
#   twin_typical, twin_ideal      scenes/kitti_twin.yaml with sequence 06's camera (the
#                                 four --set of the scene's header), 12 m/s, 5 s,
#                                 robot.realism typical / ideal
#   twin_typical_ss4, twin_ideal_ss4   the same with robot.stereo.supersampling=4 (the
#                                 sharp reference render)
#   corridor, park                scenes/corridor.yaml, scenes/outdoor.yaml as they are
#   sand                          scenes/outdoor_km.yaml's straight sand drive, 60 s,
#                                 robot.realism ideal
# each with outputs.save_images=kitti. Measured: every fifth image (KITTI 06: frames
# 0, 5, …, 50), four bands.
set -euo pipefail

if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  sed -n '2,20p' "$0" >&2
  exit 2
fi
root="$(cd "$(dirname "$0")/.." && pwd)"
bin="$(realpath "$1")"
out="$(mkdir -p "$2" && realpath "$2")"
stats_bin="$(realpath "${3:-$root/build/apps/trackbed}")"
nice_level="${NICE:-10}"
for b in "$bin" "$stats_bin"; do
  [ -x "$b" ] || { echo "image_statistics_table: $b is not an executable" >&2; exit 2; }
done
"$stats_bin" image-stats --help >/dev/null 2>&1 ||
  { echo "image_statistics_table: $stats_bin has no image-stats subcommand" >&2; exit 2; }

data_dir="${TRACKBED_DATA_DIR:-}"
if [ -z "$data_dir" ] && [ -f "$root/build/CMakeCache.txt" ]; then
  data_dir="$(sed -n 's/^TRACKBED_DATA_DIR:PATH=//p' "$root/build/CMakeCache.txt")"
fi
data_dir="${data_dir:-$root/../shared/data}"
kitti="$data_dir/kitti06"
[ -d "$kitti/image_0" ] ||
  { echo "image_statistics_table: no KITTI 06 at $kitti (set TRACKBED_DATA_DIR)" >&2; exit 2; }

mkdir -p "$out/runs" "$out/stats" "$out/vo" "$out/stereo"
cd "$root"
bin_sha="$(sha256sum "$bin" | cut -d' ' -f1)"
echo "image_statistics_table: rendering with $bin (sha256 $bin_sha), measuring with $stats_bin"
echo "$bin $bin_sha" >"$out/render_binary.txt"
git -C "$root" rev-parse HEAD >"$out/checkout_commit.txt" 2>/dev/null || true

# render NAME SCENE [--set ...]: one run, unless it is there from the same binary.
render() {
  local name="$1" scene="$2"
  shift 2
  local dir="$out/runs/$name"
  if [ -f "$dir/metrics.json" ] && [ "$(cat "$out/runs/$name.bin" 2>/dev/null)" = "$bin_sha" ]; then
    echo "  $name: there (same binary)"
    return
  fi
  rm -rf "$dir" "$out/runs/$name.bin"
  local cmd=("$bin" run "$scene" --out "$dir" --seed 1 --no-progress
             --set outputs.save_images=kitti "$@")
  printf '%q ' "${cmd[@]}" >"$out/runs/$name.cmd"
  echo >>"$out/runs/$name.cmd"
  echo "  $name: rendering"
  local start=$SECONDS
  nice -n "$nice_level" "${cmd[@]}" >"$out/runs/$name.log" 2>&1 ||
    { echo "image_statistics_table: $name failed, see $out/runs/$name.log" >&2; exit 1; }
  echo "$bin_sha" >"$out/runs/$name.bin"
  echo "  $name: $((SECONDS - start)) s"
}

twin06=(--set robot.stereo.width_px=1226 --set robot.stereo.height_px=370
        --set robot.stereo.focal_length_px=707.0912
        --set "robot.stereo.principal_point_px=[601.8873,183.1104]"
        --set drive.speed_mps=12 --set duration_s=5)
render twin_typical scenes/kitti_twin.yaml "${twin06[@]}" --set robot.realism=typical
render twin_ideal scenes/kitti_twin.yaml "${twin06[@]}" --set robot.realism=ideal
render twin_typical_ss4 scenes/kitti_twin.yaml "${twin06[@]}" --set robot.realism=typical \
  --set robot.stereo.supersampling=4
render twin_ideal_ss4 scenes/kitti_twin.yaml "${twin06[@]}" --set robot.realism=ideal \
  --set robot.stereo.supersampling=4
render corridor scenes/corridor.yaml
render park scenes/outdoor.yaml
render sand scenes/outdoor_km.yaml --set duration_s=60 --set robot.realism=ideal \
  --set "drive.waypoints=[[160,0],[172.5,27.2]]" --set drive.closed=false

echo "image_statistics_table: measuring"
twins=(twin_typical twin_ideal twin_typical_ss4 twin_ideal_ss4)
scenes=(corridor park sand)
nice -n "$nice_level" "$stats_bin" image-stats "$kitti" --count 11 \
  --json "$out/stats/kitti06.json" --csv "$out/stats/kitti06.csv" >"$out/stats/kitti06.txt"
for group in twins scenes; do
  declare -n names="$group"
  dirs=()
  for n in "${names[@]}"; do dirs+=("$out/runs/$n"); done
  nice -n "$nice_level" "$stats_bin" image-stats "${dirs[@]}" \
    --json "$out/stats/$group.json" --csv "$out/stats/$group.csv" >"$out/stats/$group.txt"
  unset -n names
done

# Visual odometry (KITTI's car bounds) on the twin's renders and on real KITTI 06's
# frames 0–50: the renders must serve `trackbed vo` as real data does.
nice -n "$nice_level" "$stats_bin" vo "$kitti" --out "$out/vo/kitti06" >"$out/vo/kitti06.txt"
for n in "${twins[@]}"; do
  nice -n "$nice_level" "$stats_bin" vo "$out/runs/$n/images" --out "$out/vo/$n" \
    >"$out/vo/$n.txt"
done

# One stereo pair per robot scene, left | right at native size: corridor at 22 s and
# the park at 58 s (the README's moments), the sand at 30 s.
for pair in corridor:000220 park:000580 sand:000300; do
  n="${pair%%:*}" f="${pair##*:}"
  python3 "$root/scripts/stereo_pair_png.py" "$out/runs/$n/images/image_0/$f.png" \
    "$out/runs/$n/images/image_1/$f.png" "$out/stereo/$n.png"
done

python3 - "$out" <<'EOF'
# tables.md: one row per folder, one column per statistic, each cell its bands top to
# bottom ("a / b / c / d").
import json, pathlib, sys

out = pathlib.Path(sys.argv[1])
columns = [("FAST", "fast_corners", "{:.0f}"), ("Shi–Tomasi", "shi_tomasi_corners", "{:.0f}"),
           ("mean gradient", "mean_gradient", "{:.1f}"), ("spectrum slope", "spectrum_slope", "{:.2f}"),
           ("grey mean", "grey_mean", "{:.0f}"), ("grey std", "grey_std", "{:.0f}"),
           ("LK tracked", "track_share", "{:.2f}")]


def rows(file, names):
    folders = json.loads((out / "stats" / file).read_text())["folders"]
    for name, f in zip(names, folders):
        cells = [" / ".join("n/a" if b[key] is None else fmt.format(b[key]) for b in f["bands"])
                 for _, key, fmt in columns]
        size = "{} × {}".format(*f["image_size"])
        yield "| {} | {} ({}) | {} |".format(name, len(f["images"]), size, " | ".join(cells))


def vo_row(name):
    m = json.loads((out / "vo" / name / "vo_metrics.json").read_text())
    g = m.get("ground_truth") or {}
    f = g.get("frame_to_frame") or {}
    if not f:
        return "| {} | {} | n/a | n/a | n/a |".format(name, m["frames"])
    return "| {} | {} | {:.2f} | {:.3f} | {:.4f} |".format(
        name, m["frames"], f["translation_error_pct"]["median"], f["rotation_error_deg"]["median"],
        f["length_ratio"]["median"])


head = "| images | images measured (size) | " + " | ".join(c[0] for c in columns) + " |"
rule = "|---" * (len(columns) + 2) + "|"
twins = ["twin_typical", "twin_ideal", "twin_typical_ss4", "twin_ideal_ss4"]
lines = ["Bands top to bottom in each cell (a / b / c / d).", "",
         "KITTI 06 and the KITTI twin (sequence 06's camera, 12 m/s):", "", head, rule]
lines += list(rows("kitti06.json", ["real KITTI 06, frames 0–50"]))
lines += list(rows("twins.json", twins))
lines += ["", "The robot's scenes:", "", head, rule]
lines += list(rows("scenes.json", ["corridor", "park", "sand"]))
lines += ["", "`trackbed vo` frame to frame (medians):", "",
          "| images | frames | translation error [%] | rotation error [°] | length ratio |",
          "|---|---|---|---|---|", vo_row("kitti06")] + [vo_row(n) for n in twins]
(out / "tables.md").write_text("\n".join(lines) + "\n")
print("\n".join(lines))
EOF
echo "image_statistics_table: tables in $out/tables.md"
