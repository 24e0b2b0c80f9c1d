"""Child process of ``test_blas_kernels.py``: the dNNM stage (:func:`ringdamper.nonlinear.stage.run_dnnm`)
of the rings whose ``{ring}_reduced.nc`` and ``{ring}_static.nc`` lie in a folder, with the configuration
and normalisation of its ``job.json``, under the OpenBLAS kernel that ``OPENBLAS_CORETYPE`` selects (read
when numpy loads OpenBLAS, hence a process of its own). Writes ``{ring}.nc`` (dnnm.nc) and
``kernels.json`` (the kernels OpenBLAS reports) into the output folder.

    python tests/nonlinear/blas_kernel_run.py INPUT_FOLDER OUTPUT_FOLDER
"""
import json
import sys
from pathlib import Path


def main(folder: Path, out: Path) -> None:
    import threadpoolctl

    from ringdamper.io import read_netcdf, write_netcdf
    from ringdamper.nonlinear.stage import run_dnnm

    job = json.loads((folder / "job.json").read_text())
    out.mkdir(parents=True, exist_ok=True)
    for ring in job["rings"]:
        ds = run_dnnm(read_netcdf(folder / f"{ring}_reduced.nc"), read_netcdf(folder / f"{ring}_static.nc"),
                      job["config"], job["target_hz"], job["omega_stuck_default"])
        write_netcdf(ds, out / f"{ring}.nc")
    kernels = sorted({i["architecture"] for i in threadpoolctl.threadpool_info() if i["internal_api"] == "openblas"})
    (out / "kernels.json").write_text(json.dumps(kernels))


if __name__ == "__main__":
    main(Path(sys.argv[1]), Path(sys.argv[2]))
