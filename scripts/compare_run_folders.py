#!/usr/bin/env python3
"""Compares two folders of run folders file by file, byte for byte, except the
fields that measure the machine rather than the run (wall_time_s,
real_time_factor, timing.*, memory.*, host and start time in JSON files, the same
columns and metrics in the sweep summaries, the *_timing files of per-frame times) and the
logs that quote them. Exit 0 when everything else is identical.

    python3 scripts/compare_run_folders.py runs/golden_before runs/golden_after

With --new-keys-allowed, the second folder may add files and, in JSON and YAML files
and in a sweep's `set` lists, keys and overrides the first has not (a feature that
leaves every earlier value as it was; the sweep files then differ only in the overrides
added): the values the first folder has must be identical. A sweep's `summary.csv` may
then add columns and its `aggregates.csv` rows of new metrics: the second folder's are
compared on the first's columns and metrics.

    python3 scripts/compare_run_folders.py --new-keys-allowed runs/before runs/ideal
"""
import csv
import io
import json
import pathlib
import re
import sys

import yaml

MACHINE_KEYS = {"wall_time_s", "real_time_factor", "timing", "memory",
                "stderr_tail", "started_utc", "host"}
MACHINE_COLUMN = re.compile(r"^(wall|timing_|mem_|host)")


def strip_json(value):
    if isinstance(value, dict):
        return {k: strip_json(v) for k, v in value.items() if k not in MACHINE_KEYS}
    if isinstance(value, list):
        return [strip_json(v) for v in value]
    return value


def strip_csv(text):
    """Drops machine columns (summary.csv) and machine metric rows (aggregates.csv)."""
    rows = list(csv.reader(io.StringIO(text)))
    if not rows:
        return rows
    keep = [i for i, name in enumerate(rows[0]) if not MACHINE_COLUMN.match(name)]
    metric = rows[0].index("metric") if "metric" in rows[0] else None
    return [[row[i] for i in keep if i < len(row)] for row in rows
            if metric is None or not MACHINE_COLUMN.match(row[metric])]


def contained(a, b):
    """Whether b holds every key, item and value of a (maps may add keys; lists of
    strings, such as a sweep's overrides, may add items)."""
    if isinstance(a, dict) and isinstance(b, dict):
        return all(k in b and contained(v, b[k]) for k, v in a.items())
    if isinstance(a, list) and isinstance(b, list):
        if len(a) == len(b) and all(contained(x, y) for x, y in zip(a, b)):
            return True
        return all(isinstance(x, str) for x in a + b) and all(x in b for x in a)
    return a == b


NEW_KEYS = False


def restricted(rows_a, rows_b):
    """rows_b on rows_a's columns (by name), and without the metric rows rows_a has not
    (aggregates.csv): what a feature that adds metrics leaves to compare."""
    if not rows_a or not rows_b or not set(rows_a[0]) <= set(rows_b[0]):
        return rows_b
    index = [rows_b[0].index(name) for name in rows_a[0]]
    rows = [[row[i] if i < len(row) else None for i in index] for row in rows_b]
    if "metric" in rows_a[0]:
        m = rows_a[0].index("metric")
        known = {row[m] for row in rows_a[1:]}
        rows = rows[:1] + [row for row in rows[1:] if row[m] in known]
    return rows


def same(a, b):
    if a.suffix in (".log", ".md") or a.name in ("stdout.txt", "stderr.txt", "summary.json"):
        return True  # these quote wall times and paths; their data is in the files above
    if a.stem.endswith("_timing"):
        return True  # wall-clock time per frame (teach_repeat_timing.csv and its plot)
    if NEW_KEYS and a.suffix in (".json", ".yaml"):
        try:
            load = json.loads if a.suffix == ".json" else yaml.safe_load
            return contained(strip_json(load(a.read_text())), strip_json(load(b.read_text())))
        except (json.JSONDecodeError, yaml.YAMLError, UnicodeDecodeError):
            pass
    if a.suffix == ".json":
        try:
            return strip_json(json.loads(a.read_text())) == strip_json(json.loads(b.read_text()))
        except (json.JSONDecodeError, UnicodeDecodeError):
            pass
    if a.suffix == ".csv" and a.name.startswith(("summary", "aggregates")):
        rows_a, rows_b = strip_csv(a.read_text()), strip_csv(b.read_text())
        if NEW_KEYS:
            rows_b = restricted(rows_a, rows_b)
        return rows_a == rows_b
    return a.read_bytes() == b.read_bytes()


def main():
    global NEW_KEYS
    args = sys.argv[1:]
    if args and args[0] == "--new-keys-allowed":
        NEW_KEYS = True
        args = args[1:]
    left, right = map(pathlib.Path, args[:2])
    files_l = {p.relative_to(left) for p in left.rglob("*") if p.is_file()}
    files_r = {p.relative_to(right) for p in right.rglob("*") if p.is_file()}
    bad = 0
    for rel in sorted(files_l ^ files_r):
        if NEW_KEYS and rel in files_r:
            continue  # a file the feature adds
        print(f"only in one: {rel}")
        bad += 1
    for rel in sorted(files_l & files_r):
        if not same(left / rel, right / rel):
            print(f"differs: {rel}")
            bad += 1
    print(f"{len(files_l & files_r)} files compared, {bad} differences")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
