#!/usr/bin/env python3
"""Writes the quick CI profile's generator config: BASE (configs/sunset_apartment.json)
with OVERRIDES (configs/quick/dataset_overrides.json) merged into it, key by key.
Used by scripts/quick_check.sh and the Slurm test (tests/slurm/slurm_matrix_test.sh).

    quick_dataset_config.py BASE OVERRIDES OUT
"""
import json
import sys


def merge(into, values):
    for key, value in values.items():
        if isinstance(value, dict):
            merge(into.setdefault(key, {}), value)
        else:
            into[key] = value


def main():
    if len(sys.argv) != 4:
        sys.exit("usage: quick_dataset_config.py BASE OVERRIDES OUT")
    with open(sys.argv[1]) as f:
        base = json.load(f)
    with open(sys.argv[2]) as f:
        overrides = json.load(f)
    overrides.pop("_comment", None)
    merge(base, overrides)
    with open(sys.argv[3], "w") as f:
        json.dump(base, f, indent=1)


if __name__ == "__main__":
    main()
