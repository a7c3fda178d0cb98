#!/usr/bin/env python3
"""Compares two folders of run folders file by file, byte for byte, except the
fields that measure the machine rather than the run (wall_time_s,
real_time_factor, timing.*, memory.*, host and start time in JSON files, the same
columns and metrics in the sweep summaries) and the logs that quote them. Exit 0 when everything else is identical.

    python3 scripts/compare_run_folders.py runs/golden_before runs/golden_after
"""
import csv
import io
import json
import pathlib
import re
import sys

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


def same(a, b):
    if a.suffix in (".log", ".md") or a.name in ("stdout.txt", "stderr.txt", "summary.json"):
        return True  # these quote wall times and paths; their data is in the files above
    if a.suffix == ".json":
        try:
            return strip_json(json.loads(a.read_text())) == strip_json(json.loads(b.read_text()))
        except (json.JSONDecodeError, UnicodeDecodeError):
            pass
    if a.suffix == ".csv" and a.name.startswith(("summary", "aggregates")):
        return strip_csv(a.read_text()) == strip_csv(b.read_text())
    return a.read_bytes() == b.read_bytes()


def main():
    left, right = map(pathlib.Path, sys.argv[1:3])
    files_l = {p.relative_to(left) for p in left.rglob("*") if p.is_file()}
    files_r = {p.relative_to(right) for p in right.rglob("*") if p.is_file()}
    bad = 0
    for rel in sorted(files_l ^ files_r):
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
