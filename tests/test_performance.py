"""The generated performance page (ringdamper.performance): every value it prints is the one of the
input it names, read back from the page; an absent source leaves its rows out."""
import json

import pandas as pd
import pytest

from ringdamper.performance import markdown, performance_table, read_markdown

MACHINE = {"cpu_model": "Test CPU", "reference_lu_s": 0.0551, "load_average_1min": 2.5}


def _write(path, text):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)


@pytest.fixture
def results(tmp_path):
    """A results folder with a design row, samples, four jobs with logs, CPU records and benchmark
    files, and two `make bench` files."""
    r = tmp_path / "results"
    _write(r / "tables" / "design_row.csv", "design,n_training,rounds,job_cpu_s,job_wall_s,reference_lu_s,"
           "job_cpu_reference_lus,zeta_max_computed\nadaptive,42,3,875.5,930.25,0.0587,14915.0,0.00203\n")
    pd.DataFrame({"gid": ["t000", "t001", "v000", "v001", "v002"],
                  "split": ["training", "training", "validation", "validation", "validation"]}).to_csv(
        r / "samples.csv", index=False)
    for job, cpu, start, end in (("dnnm/t000", 6.5, "21:00:00,000", "21:00:06,500"),
                                 ("dnnm/t001", 9.5, "21:00:01,000", "21:00:10,250"),
                                 ("dnnm/v000", 7.0, "21:00:02,000", "21:00:09,000"),
                                 ("static/t000", 1.25, "20:58:30,000", "20:58:31,000")):
        _write(r / "benchmarks" / f"{job}.tsv", "s\tcpu_time\n1.0\t1.0\n")
        _write(r / "logs" / f"{job}.log", f"2026-12-01 {start} INFO a: start\n2026-12-01 {end} INFO a: end\n")
        _write(r / "logs" / f"{job}.cpu.json", json.dumps({"cpu_s": cpu}))
    # a job's log without a benchmark file (the page's own rule) does not stretch the span
    _write(r / "logs" / "performance_table.log", "2026-12-01 23:00:00,000 INFO a: late\n")
    _write(r / "benchmarks" / "geometry_chain.json", json.dumps({
        "machine": MACHINE, "chain_default_H_s": 17.25, "mesh_model_s": 1.5, "static_s": 0.75, "reduced_s": 2.5,
        "dnnm_H1_s": 2.0, "dnnm_H3_s": 8.5,
        "frf_table3": [{"seconds": 12.0, "cpu_seconds": 11.5}, {"seconds": 9.0, "cpu_seconds": 7.25}],
        "peak_rss_mb": 650.0, "total_wall_s": 60.0}))
    _write(r / "benchmarks" / "dnnm.json", json.dumps({
        "machine": MACHINE, "default": {"cpu_s": 8.5, "cpu_reference_lus": 154.3}, "median_cpu_s": 6.25,
        "cpu_max_over_median": 4.125, "peak_rss_mb": 700.0, "total_wall_s": 90.0}))
    _write(r / "benchmarks" / "static_synthetic.json", json.dumps({
        "machine": MACHINE, "Q2": {"element": "Q2", "penalty": {"solve_s": 3.75}, "lagrange": {"solve_s": 4.25}},
        "Q1": {"element": "Q1", "penalty": {"solve_s": 3.5}}}))
    return r


def test_the_page_prints_the_values_of_its_inputs(results):
    page = read_markdown(markdown(performance_table(results)))
    expected = {
        "design": "adaptive", "training rings": "42", "adaptive rounds": "3", "job CPU": "875.5",
        "job wall time, summed": "930.2", "reference LU, campaign's machine": "0.0587",
        "job CPU in reference LUs": "14915", "validation rings": "3", "jobs": "4",
        # 20:58:30.000 to 21:00:10.250
        "wall time, first to last record of the jobs' logs": f"{100.25 / 60:.4g}",
        "dNNM job CPU, median of 3": "7", "dNNM job CPU, largest": "9.5",
        "static contact job CPU, median of 1": "1.25",
        "CPU": "Test CPU", "reference LU, bench's machine": "0.0551",
        "load average when the bench started": "2.5",
        "chain mesh → static → reduced → dNNM, default ring, wall": "17.25", "reduction, wall": "2.5",
        "dNNM + E-EBM, default ring, H = 1, wall": "2", "dNNM + E-EBM, default ring, H = 3, wall": "8.5",
        "Table 3 forced response CPU, default ring, least of 2": "7.25",
        "Table 3 forced response CPU, default ring, most": "11.5",
        "dNNM CPU, default ring": "8.5", "dNNM CPU, default ring, in reference LUs": "154.3",
        "dNNM CPU, median of the median-cost rings": "6.25", "dNNM CPU, slowest ring over that median": "4.125",
        "peak memory, largest (dnnm)": "700",
        "static solver, two blocks, Q2, penalty": "3.75", "static solver, two blocks, Q2, lagrange": "4.25",
        "static solver, two blocks, Q1, penalty": "3.5",
    }
    assert {k: page.get(k) for k in expected} == expected


def test_absent_sources_leave_their_rows_out(results):
    (results / "benchmarks" / "dnnm.json").unlink()
    (results / "tables" / "design_row.csv").unlink()
    page = read_markdown(markdown(performance_table(results)))
    assert "training rings" not in page and "dNNM CPU, default ring" not in page
    assert page["jobs"] == "4" and page["dNNM + E-EBM, default ring, H = 3, wall"] == "8.5"


def test_every_quantity_is_named_once(results):
    table = performance_table(results)
    assert table.quantity.is_unique
