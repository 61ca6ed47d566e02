#!/usr/bin/env python3
"""The peer table of docs/performance.md from `footprint eval --peers`'s results.json.

    python3 bench/peer-table.py eval/results.json

Prints, per scene, interior RMSE, interior mean FLIP and flicker of fa-rough and of each peer at
1 spp, and whether fa-rough is the best of them in RMSE and in FLIP.
"""
import json
import sys

MODES = ["fa-rough", "lean", "toksvig", "specular-aa", "stochastic"]


def number(x, digits=4):
    return "—" if x is None else f"{x:.{digits}f}"


def main(path):
    with open(path) as f:
        results = json.load(f)
    head = "| scene | measure | " + " | ".join(MODES) + " | fa-rough best |"
    print(head)
    print("|" + "---|" * (len(MODES) + 3))
    for scene in results["scenes"]:
        methods = {m["method"]: m for m in scene["methods"] if m["spp"] == 1}
        if not all(mode in methods for mode in MODES):
            continue
        for key, label in [("rmse_interior", "RMSE"), ("flip_interior", "FLIP"),
                           ("flicker", "flicker")]:
            values = [methods[mode].get(key) for mode in MODES]
            best = ""
            if key != "flicker" and None not in values:
                best = "yes" if values[0] <= min(values[1:]) else "no"
            print(f"| {scene['name']} | {label} | "
                  + " | ".join(number(v, 3 if key == "flicker" else 4) for v in values)
                  + f" | {best} |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
