"""Checks that ParaView's XDMF reader opens a run's results.xmf and sees what
results.h5 holds: the number of time steps and their values, the number of
points, the array names, and value ranges against the HDF5 file itself.

Run with pvpython (Debian package `paraview`):

  pvpython tests/check_xdmf_paraview.py RUN_DIR
      check the results.xmf of a finished run
  pvpython tests/check_xdmf_paraview.py --gearsph BUILD/gearsph
      run small plate jobs: one checked while `gearsph run` is still writing
      (ParaView opens a live run) and again after it is killed with SIGKILL,
      one checked when it has finished

Exits 0 on success, 1 with a message on the first failed check.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import h5py  # Debian python3-h5py; pvpython uses the system Python
from paraview import servermanager
from paraview.simple import XDMFReader

SCALARS = ["stress_xx", "stress_yy", "stress_xy", "stress_zz", "pressure",
           "von_mises", "density", "body_id", "particle_id"]
VECTORS = ["velocity", "displacement"]

SMALL_JOB = {"name": "paraview-check",
             "scene": {"type": "plate", "length_m": 0.1, "thickness_m": 0.01},
             "discretization": {"spacing_m": 0.002},
             "time": {"end_s": 0.01}, "output": {"frames": 10}}
# Long enough never to finish while the check reads it (it is killed after).
LIVE_JOB = dict(SMALL_JOB, name="paraview-live",
                discretization={"spacing_m": 0.001}, time={"end_s": 0.2},
                output={"frames": 400})


class CheckFailed(Exception):
    pass


def expect(condition, message):
    if not condition:
        raise CheckFailed(message)


def open_settled(path, attempts=10):
    """Opens results.h5, retrying briefly: a reader that catches a running job's
    flush mid-way sees the new end-of-file address in the superblock before
    the file has grown to it ("truncated file"). A killed run's file has no
    such moment (the crash-point test kills a run between every two writes)."""
    for attempt in range(1, attempts + 1):
        try:
            return h5py.File(path, "r", locking=False)
        except OSError:
            if attempt == attempts:
                raise
            time.sleep(0.02)


def committed(h5):
    """Frames a reader may trust: those whose step marker was written."""
    steps = h5["frames/step"][:]
    n = 0
    while n < len(steps) and steps[n] >= 0:
        n += 1
    return n


def fetch(reader, t):
    reader.UpdatePipeline(t)
    data = servermanager.Fetch(reader)
    return data.GetBlock(0) if data.IsA("vtkMultiBlockDataSet") else data


def check_frame(grid, h5, k, n):
    expect(grid.GetNumberOfPoints() == n,
           f"frame {k}: {grid.GetNumberOfPoints()} points, results.h5 has {n}")
    pd = grid.GetPointData()
    names = {pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())}
    expect(names == set(SCALARS + VECTORS), f"frame {k}: arrays {sorted(names)}")
    for name in VECTORS:
        expect(pd.GetArray(name).GetNumberOfComponents() == 3, f"{name} is not a vector")
    for name in SCALARS:
        array = pd.GetArray(name)
        values = h5["frames/" + name][k]
        lo, hi = array.GetRange()
        expect((lo, hi) == (float(values.min()), float(values.max())),
               f"frame {k}: {name} range ({lo}, {hi}) but results.h5 has "
               f"({values.min()}, {values.max()})")
    expect(pd.GetArray("particle_id").GetRange() == (0.0, float(n - 1)), "particle ids")
    expect(pd.GetArray("von_mises").GetRange()[0] >= 0.0, "negative von Mises stress")
    xyz = h5["frames/position"][k]
    bounds = grid.GetBounds()
    want = (xyz[:, 0].min(), xyz[:, 0].max(), xyz[:, 1].min(), xyz[:, 1].max())
    expect(tuple(bounds[:4]) == tuple(float(v) for v in want),
           f"frame {k}: bounds {bounds} differ from /frames/position")


def check_run(run_dir, live=False):
    xmf = os.path.join(run_dir, "results.xmf")
    expect(os.path.exists(xmf), f"no {xmf}")
    started = time.monotonic()
    reader = XDMFReader(FileNames=[xmf])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues) if reader.TimestepValues else []
    with open_settled(os.path.join(run_dir, "results.h5")) as h5:
        frames = committed(h5)
        n = h5["meta"].attrs["particles"]
        # A live run's xmf lags results.h5; a finished one matches it.
        expect(1 <= len(times) <= frames if live else len(times) == frames,
               f"{len(times)} time steps in results.xmf, {frames} frames in results.h5")
        stored = h5["frames/time"][: len(times)]
        expect(all(a == b for a, b in zip(times, stored)), "time values differ from /frames/time")
        for k in sorted({0, len(times) // 2, len(times) - 1}):
            check_frame(fetch(reader, times[k]), h5, k, n)
    status = "running or killed run" if live else "finished run"
    print(f"ok ({status}): {len(times)} time steps, {n} points, "
          f"{len(SCALARS) + len(VECTORS)} arrays, read in {time.monotonic() - started:.2f} s")


def run_gearsph(gearsph, job, out, wait=True):
    path = os.path.join(out, "job.json")
    with open(path, "w") as f:
        json.dump(job, f)
    cmd = [gearsph, "run", path, "--out", os.path.join(out, "run"), "--quiet"]
    if wait:
        subprocess.run(cmd, check=True)
        return None
    return subprocess.Popen(cmd)


def check_live_run(run_dir, attempts=5):
    """A reader that opens results.h5 while the running job flushes it finds
    the superblock's new end-of-file before the file has grown to it
    ("truncated file"): ParaView then reports an error and shows no values
    (seen on a loaded machine, with builds running beside the tests). A
    person presses reload; so does this check, a few times, before it fails."""
    for attempt in range(1, attempts + 1):
        try:
            check_run(run_dir, live=True)
            return
        except CheckFailed as e:
            if attempt == attempts:
                raise
            print(f"live run read mid-flush ({e}); reading it again", file=sys.stderr)
            time.sleep(0.2)


def check_live(gearsph, tmp):
    proc = run_gearsph(gearsph, LIVE_JOB, tmp, wait=False)
    run_dir = os.path.join(tmp, "run")
    try:
        deadline = time.monotonic() + 60
        while not os.path.exists(os.path.join(run_dir, "results.xmf")):
            expect(proc.poll() is None, "gearsph run ended before writing results.xmf")
            expect(time.monotonic() < deadline, "no results.xmf after 60 s")
            time.sleep(0.05)
        time.sleep(1.0)  # let a few more frames arrive
        check_live_run(run_dir)
        expect(proc.poll() is None, "the run had finished: the live check proved nothing; "
               "make LIVE_JOB longer")
    finally:
        proc.kill()
        proc.wait()
    check_run(run_dir, live=True)  # what a killed run leaves


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run_dir", nargs="?", help="a run directory with results.xmf")
    parser.add_argument("--gearsph", help="run jobs with this gearsph executable and check them")
    args = parser.parse_args()
    if not args.run_dir and not args.gearsph:
        parser.error("give RUN_DIR or --gearsph")
    try:
        if args.run_dir:
            check_run(args.run_dir)
        if args.gearsph:
            with tempfile.TemporaryDirectory(prefix="gearsph_pv_") as tmp:
                check_live(args.gearsph, os.path.join(tmp))
            with tempfile.TemporaryDirectory(prefix="gearsph_pv_") as tmp:
                run_gearsph(args.gearsph, SMALL_JOB, tmp)
                check_run(os.path.join(tmp, "run"))
    except CheckFailed as e:
        print(f"check_xdmf_paraview: FAILED: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
