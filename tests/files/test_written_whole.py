"""A stage file is written whole or not at all (io.written_whole): a process killed with SIGKILL in the
middle of writing a NetCDF file, after half of its bytes reached the disk, leaves at the file's path
the previous file, or no file, never the half, and the next write of the file removes the half; a
write that raises leaves no temporary behind."""
import signal
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

from ringdamper.io import read_netcdf, variable, write_netcdf

# Writes a NetCDF file through write_netcdf with xarray's writer replaced by one that writes the file
# whole, cuts it to half and kills its own process: a kill at a known point of the write.
KILLED_WHILE_WRITING = """
import os, signal, sys
import xarray as xr
from ringdamper.io import variable, write_netcdf

whole = xr.Dataset.to_netcdf

def half_then_killed(self, path, **kwargs):
    whole(self, path, **kwargs)
    with open(path, "r+b") as fh:
        fh.truncate(os.path.getsize(path) // 2)
    os.kill(os.getpid(), signal.SIGKILL)

xr.Dataset.to_netcdf = half_then_killed
write_netcdf(xr.Dataset({"x": variable("i", [3.0, 4.0], "m", "new")}), sys.argv[1])
"""


def old_file(path) -> None:
    write_netcdf(xr.Dataset({"x": variable("i", [1.0, 2.0], "m", "old")}), path)


@pytest.mark.parametrize("previous", [False, True], ids=["new file", "overwrite"])
def test_a_process_killed_in_the_middle_of_a_write_leaves_no_half_file(tmp_path, previous):
    path = tmp_path / "dnnm.nc"
    if previous:
        old_file(path)
    run = subprocess.run([sys.executable, "-c", KILLED_WHILE_WRITING, str(path)], capture_output=True, text=True)
    assert run.returncode == -signal.SIGKILL, run.stderr
    assert path.exists() == previous
    if previous:
        np.testing.assert_array_equal(read_netcdf(path)["x"].values, [1.0, 2.0])
    leftovers = [p.name for p in tmp_path.iterdir() if p != path]
    assert len(leftovers) == 1 and leftovers[0].startswith(".dnnm.")   # the killed process's half
    write_netcdf(xr.Dataset({"x": variable("i", [5.0, 6.0], "m", "rerun")}), path)   # the job rerun
    assert [p.name for p in tmp_path.iterdir()] == ["dnnm.nc"]
    np.testing.assert_array_equal(read_netcdf(path)["x"].values, [5.0, 6.0])


def test_a_write_that_raises_keeps_the_previous_file_and_leaves_no_temporary(tmp_path, monkeypatch):
    path = tmp_path / "dnnm.nc"
    old_file(path)
    whole = xr.Dataset.to_netcdf

    def written_then_raises(self, target, **kwargs):
        whole(self, target, **kwargs)
        raise OSError("disk full")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", written_then_raises)
    with pytest.raises(OSError, match="disk full"):
        write_netcdf(xr.Dataset({"x": variable("i", [3.0, 4.0], "m", "new")}), path)
    np.testing.assert_array_equal(read_netcdf(path)["x"].values, [1.0, 2.0])
    assert [p.name for p in tmp_path.iterdir()] == ["dnnm.nc"]
