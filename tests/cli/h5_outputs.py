#!/usr/bin/python3
"""The HDF5 and XDMF files of a run describe themselves and open in every reader.

    h5_outputs.py CGDEM CASE WORK

Runs CASE (a tiny case with air) into WORK/run, then checks, printing what it measured:
  * every .h5 of the run folder (h5py): every dataset has non-empty string attributes
    "units" and "description"; every file has cgdem_revision, config and description, and
    time (with time_units = "s") and step;
  * every .xdmf (xml.etree): XDMF 3, a temporal collection, and every HDF DataItem names an
    existing file and dataset of the stated Dimensions, NumberType and Precision; every XML
    DataItem holds as many numbers as its Dimensions; a Polyvertex topology has one
    connectivity entry per parcel; a 3DCoRectMesh has the nodes of /grid/n;
  * meshio, if it is installed (skipped with a message otherwise): its TimeSeriesReader
    opens particles.xdmf and, at every step, gives the positions and velocities of that
    step's file (air.xdmf: meshio has no structured-grid topology; see docs);
  * a truncated and a garbage .h5 given as [[particles.file]] stop the run with a non-zero
    exit and exactly one line on stderr naming the file, without HDF5's own error stack.
Exits non-zero on the first failed check (tolerance 0: shapes, types and values must match).
"""
import glob
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

cgdem, case, work = sys.argv[1:4]
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)
    return ok


def as_str(v):
    return v.decode() if isinstance(v, bytes) else str(v)


shutil.rmtree(work, ignore_errors=True)
run = os.path.join(work, "run")
r = subprocess.run([cgdem, "run", case, "--set", "air.dx=1e-3", "--output", run], capture_output=True, text=True)
if r.returncode != 0:
    sys.exit(f"the run failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")

# ---------------------------------------------------------------- HDF5 files
h5files = sorted(glob.glob(os.path.join(run, "*.h5")))
check(len(h5files) >= 5, f"at least 5 .h5 files (particles, air, last_good), found {len(h5files)}")
n_sets = 0
for path in h5files:
    name = os.path.basename(path)
    with h5py.File(path, "r") as f:
        for key in ("cgdem_revision", "config", "description", "time_units"):
            check(key in f.attrs and as_str(f.attrs[key]) != "", f"{name}: file attribute '{key}'")
        check(as_str(f.attrs.get("time_units", "")) == "s", f"{name}: time_units is 's'")
        check("time" in f.attrs and "step" in f.attrs, f"{name}: time and step attributes")
        sets = []
        f.visititems(lambda k, o: sets.append((k, o)) if isinstance(o, h5py.Dataset) else None)
        for k, d in sets:
            n_sets += 1
            for a in ("units", "description"):
                check(a in d.attrs and as_str(d.attrs[a]).strip() != "", f"{name}:/{k} has '{a}'")
print(f"{len(h5files)} .h5 files, {n_sets} datasets: every one has units and description")

# ---------------------------------------------------------------- XDMF indexes
types = {"Float": "f", "Int": "i", "UInt": "u"}
n_items = 0
xdmfs = sorted(glob.glob(os.path.join(run, "*.xdmf")))
check(sorted(map(os.path.basename, xdmfs)) == ["air.xdmf", "particles.xdmf"], f"two indexes, found {xdmfs}")
for path in xdmfs:
    root = ET.parse(path).getroot()
    check(root.tag == "Xdmf" and root.get("Version", "").startswith("3"), f"{path}: XDMF 3")
    coll = root.find("Domain/Grid")
    check(coll is not None and coll.get("CollectionType") == "Temporal", f"{path}: temporal collection")
    steps = coll.findall("Grid")
    for g in steps:
        for item in g.iter("DataItem"):
            dims = [int(x) for x in item.get("Dimensions").split()]
            if item.get("Format") == "XML":
                check(len(item.text.split()) == int(np.prod(dims)), f"{path}: XML DataItem of {dims}")
                continue
            n_items += 1
            fname, dset = item.text.strip().split(":")
            h5path = os.path.join(os.path.dirname(path), fname)
            if not check(os.path.exists(h5path), f"{path}: {fname} exists"):
                continue
            with h5py.File(h5path, "r") as f:
                if not check(dset in f, f"{fname}:{dset} exists"):
                    continue
                d = f[dset]
                check(list(d.shape) == dims, f"{fname}:{dset} shape {d.shape} == Dimensions {dims}")
                check(d.dtype.kind == types[item.get("NumberType")], f"{fname}:{dset} type {d.dtype}")
                check(d.dtype.itemsize == int(item.get("Precision")), f"{fname}:{dset} precision {d.dtype}")
        topo = g.find("Topology")
        if topo.get("TopologyType") == "Polyvertex":
            n = int(topo.get("NumberOfElements"))
            conn = topo.find("DataItem")
            if check(conn is not None, f"{path}: Polyvertex has its connectivity"):
                fname, dset = conn.text.strip().split(":")
                with h5py.File(os.path.join(run, fname), "r") as f:
                    check(np.array_equal(f[dset][:, 0], np.arange(n)), f"{fname}: connectivity is 0..{n - 1}")
        elif topo.get("TopologyType") == "3DCoRectMesh":
            fname = g.find("Attribute/DataItem").text.strip().split(":")[0]
            with h5py.File(os.path.join(run, fname), "r") as f:
                want = [int(x) + 1 for x in f["grid/n"][()][::-1]]
            check([int(x) for x in topo.get("Dimensions").split()] == want, f"{fname}: 3DCoRectMesh nodes {want}")
    print(f"{os.path.basename(path)}: {len(steps)} steps")
print(f"{n_items} HDF DataItems: file, dataset, shape, type and precision match")

# ---------------------------------------------------------------- meshio
try:
    import meshio
except ImportError:
    meshio = None
if meshio is None:
    print("meshio: SKIPPED (python3-meshio is not installed)")
else:
    with meshio.xdmf.TimeSeriesReader(os.path.join(run, "particles.xdmf")) as reader:
        points, cells = reader.read_points_cells()
        check(len(cells) == 1 and cells[0].type == "vertex" and len(cells[0].data) == len(points),
              "meshio: one vertex cell per parcel")
        for k in range(reader.num_steps):
            t, point_data, _ = reader.read_data(k)
            snap = sorted(glob.glob(os.path.join(run, "particles_*.h5")))[k]
            with h5py.File(snap, "r") as f:
                check(t == f.attrs["time"], f"meshio step {k}: time {t}")
                check(np.array_equal(point_data["position"], f["particles/x"][()]), f"meshio step {k}: positions")
                check(np.array_equal(point_data["velocity"], f["particles/v"][()]), f"meshio step {k}: velocities")
        from importlib.metadata import version
        print(f"meshio {version('meshio')}: particles.xdmf, {reader.num_steps} steps of {len(points)} parcels, "
              "positions and velocities equal to the files")

# ---------------------------------------------------------------- damaged input files
with open(case) as f:
    text = f.read()
good = os.path.join(run, "last_good.h5")
with open(good, "rb") as f:
    data = f.read()
damaged = {"truncated.h5": data[: len(data) // 2], "garbage.h5": b"\x89HDF\r\n\x1a\n" + b"\x00" * 4000}
for fname, content in damaged.items():
    p = os.path.join(work, fname)
    with open(p, "wb") as f:
        f.write(content)
    bad_case = os.path.join(work, "from_" + fname.replace(".h5", ".toml"))
    with open(bad_case, "w") as f:
        # the [[particles.insert]] block (up to the next blank line) becomes a file input
        f.write(re.sub(r"\[\[particles\.insert\]\]\n(.+\n)*",
                       f'[[particles.file]]\npath = "{fname}"\nspecies = "powder"\n', text))
    r = subprocess.run([cgdem, "run", bad_case, "--output", os.path.join(work, "out_" + fname)],
                       capture_output=True, text=True)
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    print(f"{fname}: exit {r.returncode}, {len(lines)} line(s) on stderr: {r.stderr.strip()!r}")
    check(r.returncode != 0, f"{fname}: non-zero exit")
    check(len(lines) == 1, f"{fname}: exactly one line on stderr")
    check("HDF5-DIAG" not in r.stderr and "minor:" not in r.stderr, f"{fname}: no HDF5 error stack")
    check(p in r.stderr, f"{fname}: the message names the file")

if failures:
    sys.exit(f"{len(failures)} check(s) failed")
print("all checks passed")
