"""A rule script's own CPU record: what the process and the workers it waited for used, not a sample;
and the design row's job times, which read it and fall back to Snakemake's sample only without it."""
import json
import os
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

from ringdamper.campaign.adaptive.report import job_times
from ringdamper.logs import cpu_record, read_cpu_seconds

# A rule script in miniature: it logs to a file, burns CPU in itself and in one worker process it waits
# for, and prints the CPU each counted for itself just before it exits.
SCRIPT = """
import json, sys, time
from concurrent.futures import ProcessPoolExecutor
from ringdamper.logs import to_file

def burn(seconds):
    start = time.process_time()
    while time.process_time() - start < seconds:
        sum(i * i for i in range(1000))
    return time.process_time()

if __name__ == "__main__":
    to_file(sys.argv[1])
    with ProcessPoolExecutor(1) as pool:
        worker = pool.submit(burn, 0.4).result()
    burn(0.3)
    print(json.dumps({"own": time.process_time(), "worker": worker}))
"""


def test_the_record_counts_the_script_and_the_workers_it_waited_for(tmp_path):
    log = tmp_path / "logs" / "dnnm" / "t000.log"
    script = tmp_path / "job.py"
    script.write_text(SCRIPT)
    package_root = str(Path(__file__).resolve().parents[1])  # the package under test, whatever is installed
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([package_root, os.environ.get("PYTHONPATH", "")])}
    done = subprocess.run([sys.executable, str(script), str(log)], capture_output=True, text=True, check=True,
                          env=env)
    counted = json.loads(done.stdout)
    record = json.loads(cpu_record(log).read_text())
    assert cpu_record(log) == log.parent / "t000.cpu.json"
    # the script's own time, read at exit, is at least what it counted a moment before (and not much more)
    assert counted["own"] <= record["user_s"] + record["system_s"] <= counted["own"] + 0.2
    # the worker's time arrives through getrusage's children once the pool has joined it
    assert counted["worker"] <= record["children_cpu_s"] <= counted["worker"] + 0.2
    assert record["cpu_s"] == pytest.approx(record["user_s"] + record["system_s"] + record["children_cpu_s"])
    assert read_cpu_seconds(cpu_record(log)) == record["cpu_s"]


def write_benchmark(path, wall_s, sampled_cpu_s):
    pd.DataFrame({"s": [wall_s], "cpu_time": [sampled_cpu_s]}).to_csv(path, sep="\t", index=False)


def test_job_times_take_the_record_and_fall_back_to_the_sample_only_without_one(tmp_path):
    benchmarks = [tmp_path / "a.tsv", tmp_path / "b.tsv"]
    write_benchmark(benchmarks[0], 41.2, 14.4)  # a long job: the sample stopped at its 30 s poll
    write_benchmark(benchmarks[1], 3.0, 2.5)
    records = [tmp_path / "a.cpu.json", tmp_path / "b.cpu.json"]
    records[0].write_text(json.dumps({"cpu_s": 39.8}))
    times = job_times(benchmarks, records)
    assert times == {"job_cpu_s": pytest.approx(39.8 + 2.5), "job_wall_s": pytest.approx(44.2), "sampled_jobs": 1}
    with pytest.raises(ValueError):
        job_times(benchmarks, records[:1])
