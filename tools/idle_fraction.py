"""Idle fraction of the cores during a Snakemake run, from its log (the run's stderr or
.snakemake/log/*.snakemake.log): each job's start (the timestamp above its ``rule``/``checkpoint``
block), its threads (``threads:``, 1 when not printed) and its end (``Finished jobid``) give the busy
core-seconds; idle fraction = 1 - busy / (cores x wall), wall from the first start to the last end.
Timestamps have a resolution of 1 s.

    python -m tools.idle_fraction LOG --cores 2 [--span RULE]

``--span RULE``: the same fraction from the first start to the last end of the jobs of RULE (for
``adaptive_round``: the stretch of the run in which the rounds alternate with their rings).
"""
from __future__ import annotations

import argparse
import re
from datetime import datetime

STAMP = re.compile(r"^\[(\w{3} \w{3} +\d+ \d\d:\d\d:\d\d \d{4})\]$")
START = re.compile(r"^(?:local)?(?:rule|checkpoint) (\w+):$")
FINISHED = re.compile(r"^Finished jobid: (\d+)")


def jobs(lines) -> list[dict]:
    """Per job: rule, threads, start and end (datetime) from the log's lines."""
    found, stamp, current = {}, None, None
    for raw in lines:
        line = raw.rstrip("\n")
        if match := STAMP.match(line):
            stamp = datetime.strptime(match.group(1), "%a %b %d %H:%M:%S %Y")
            current = None
        elif match := START.match(line):
            current = {"rule": match.group(1), "threads": 1, "start": stamp}
        elif current is not None and (match := re.match(r"^\s+jobid: (\d+)", line)):
            found[int(match.group(1))] = current
        elif current is not None and (match := re.match(r"^\s+threads: (\d+)", line)):
            current["threads"] = int(match.group(1))
        elif match := FINISHED.match(line.strip()):
            if int(match.group(1)) in found:
                found[int(match.group(1))]["end"] = stamp
    return [j for j in found.values() if "end" in j and j["rule"] != "all"]


def idle_fraction(records: list[dict], cores: int, windows=None) -> float:
    """1 - busy core-seconds / (cores x seconds) over the run, or over ``windows`` [(start, end)]."""
    if windows is None:
        windows = [(min(j["start"] for j in records), max(j["end"] for j in records))]
    total = busy = 0.0
    for lo, hi in windows:
        total += cores * (hi - lo).total_seconds()
        for j in records:
            overlap = (min(hi, j["end"]) - max(lo, j["start"])).total_seconds()
            busy += min(j["threads"], cores) * max(overlap, 0.0)
    return 1.0 - busy / total if total > 0 else float("nan")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("log")
    parser.add_argument("--cores", type=int, required=True)
    parser.add_argument("--span", help="restrict to the span of the jobs of this rule")
    args = parser.parse_args()
    with open(args.log) as fh:
        records = jobs(fh)
    if args.span:
        spanned = [j for j in records if j["rule"] == args.span]
        window = (min(j["start"] for j in spanned), max(j["end"] for j in spanned))
        print(f"{len(spanned)} {args.span} jobs over {(window[1] - window[0]).total_seconds():.0f} s: idle "
              f"fraction {idle_fraction(records, args.cores, [window]):.3f}")
    wall = (max(j["end"] for j in records) - min(j["start"] for j in records)).total_seconds()
    print(f"{len(records)} jobs, {wall:.0f} s wall on {args.cores} cores: idle fraction "
          f"{idle_fraction(records, args.cores):.3f}")


if __name__ == "__main__":
    main()
