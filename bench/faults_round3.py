"""The fault catalogue's third round (issue 35): each fault class of that round, tried with
values of its own (none from the issue's report), with its exact outcome. ``bench/faults_maps.py``
adds ``ROUND3`` to ``MAP_CATALOGUE``; the entries' form is described in ``bench/faults.py``."""

from __future__ import annotations

import math

import numpy as np

from bench._fault_helpers import E

C = "cli"


def _cli(*argv):
    from bench.faults_maps import _cli as cli

    return cli(*argv)


MAT = ("--alpha", "3.1", "--K-s", "0.024")
MAP = ("map", "--case", "coupled", *MAT, "--out", "/nonexistent-flexmm/map3")
POINT = ("point", *MAT, "--K-theta", "0.0205", "--case", "coupled", "--k", "1.1")
SOLITON = ("soliton", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.02151", "--k",
           "0.92991", "--case", "rotation")


def _params(**kw):
    from numerics.maps import MapParameters

    args = dict(case="coupled", alpha=3.1, K_s=0.024, delta=(0.0035,), k=(1.1,),
                amplitude=0.015, N=120, t_end=800.0)
    args.update(kw)
    return MapParameters(**args)


def _dangling_out():
    import shutil
    import tempfile
    from pathlib import Path

    d = Path(tempfile.mkdtemp())
    try:
        (d / "out").symlink_to(d / "gone" / "away")
        return _cli("map", "--case", "rotation", *MAT, "--delta", "0.0035", "--k", "1.1",
                    "--theory-only", "--out", str(d / "out"))
    finally:
        shutil.rmtree(d, ignore_errors=True)


def _spec(text):
    from numerics.maps import parse_spec

    return parse_spec(text, "--delta")


def _gain(k, q=(0.12,), theory="semi-discrete NLS", **kw):
    from numerics import Material, theory_gain

    kw = kw or {"amplitude": 0.015}
    return theory_gain(theory, Material(3.1, 0.024, 0.0205), "coupled", k, offset=list(q),
                       **kw)


def _snap(k=1.1, N=120, rel_tol=1e-3):
    from numerics import snap_wavenumber

    return snap_wavenumber(k, N, rel_tol=rel_tol)


def _generated(name, *args):
    import generated.lattice_coefficients as co

    return getattr(co, name)(*args)


def _lock(content):
    """Take the store lock of a map beside a lock file made by ``content(path)``: what the
    log said (or the error)."""
    import shutil
    import tempfile
    from pathlib import Path

    from numerics.maps import store_lock

    d = Path(tempfile.mkdtemp())
    try:
        content(d / "map.zarr.lock")
        seen = []
        with store_lock(d / "map.zarr", log=seen.append):
            pass
        return seen
    finally:
        shutil.rmtree(d, ignore_errors=True)


def _record(**fields):
    import json

    return lambda p: p.write_text(json.dumps(fields))


def _damaged_store(tamper, other=None):
    """A theory-only 2 x 2 map store (alpha 3.1, K_s 0.024) damaged by ``tamper(path)``,
    then opened again with the same (or ``other``) parameters: (log lines, done flags of
    the reopened store, whether xr.open_zarr reads it as the README shows)."""
    import shutil
    import tempfile
    import warnings
    from pathlib import Path

    import xarray as xr

    from numerics.maps import open_or_create

    d = Path(tempfile.mkdtemp())
    try:
        params = _params(delta=(0.0035, -0.002), k=(1.1, 1.6), theory_only=True, block=1)
        open_or_create(d / "map.zarr", params, log=lambda *_: None)
        tamper(d / "map.zarr")
        seen = []
        ds = open_or_create(d / "map.zarr", other or params, log=seen.append)
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            try:
                xr.open_zarr(d / "map.zarr").close()
                readable = True
            except Exception:  # noqa: BLE001 - what a user would see fail
                readable = False
        return seen, ds["done_predicted"].values.tolist(), readable
    finally:
        shutil.rmtree(d, ignore_errors=True)


def _write(name, data):
    def tamper(path):
        (path / name).write_bytes(data)
    return tamper


def _remove(name):
    def tamper(path):
        (path / name).unlink()
    return tamper


def _mark_predicted(path):
    import zarr

    zarr.open_group(str(path), mode="r+", use_consolidated=False)["done_predicted"][0, 1] = True


def _damaged(name):
    return lambda r: (len(r[0]) == 2 and f"damaged: {name};" in r[0][0]
                      and "rebuilt from this map's parameters" in r[0][0]
                      and "other parameters" not in " ".join(r[0]) and r[2])


def _undefined(alpha, K_s, K_theta):
    from numerics import Material
    from numerics.theory import nls_undefined

    return nls_undefined("semi-discrete NLS", Material(alpha, K_s, K_theta), "coupled", 1.1)


def _public_k_functions():
    """The public functions of numerics that take a carrier k, each called with ``k``."""
    import numerics as nm

    mat = nm.Material(3.1, 0.024, 0.0205)
    return {
        "mi_gain": lambda k: nm.mi_gain(mat, "coupled", k, 0.015, [0.1]),
        "plane_wave": lambda k: nm.plane_wave(mat, "coupled", k, 0.015),
        "nls_summary": lambda k: nm.nls_summary(mat, "coupled", k, amplitude=0.015),
        "theory_gain": lambda k: nm.theory_gain("paper NLS", mat, "coupled", k,
                                                offset=[0.1], amplitude=0.015),
        "snap_wavenumber": lambda k: nm.snap_wavenumber(k, 120),
        "predict_growth": lambda k: nm.predict_growth(mat, "coupled", k, 0.015, N=120,
                                                      t_end=800.0),
        "soliton": lambda k: nm.soliton(mat, "coupled", k, 0.002),
    }


#: a bad k and what it must raise (every function, the same check)
BAD_K = [(math.nan, ValueError), (-1.1, ValueError), (True, TypeError), (1.1 + 0j, TypeError),
         ("1.1", TypeError)]

def _blosc_header(nbytes, cbytes, flags=0x01, blocksize=None):
    """A Blosc 1 frame's 16 header bytes (version 2, typesize 8)."""
    blocksize = nbytes if blocksize is None else blocksize
    return (bytes((2, 1, flags, 8)) + nbytes.to_bytes(4, "little")
            + blocksize.to_bytes(4, "little") + cbytes.to_bytes(4, "little"))


def _garbage(want):
    """(what, bytes) written over a chunk of ``want`` decoded bytes: whatever its bytes, the
    chunk is damaged and never decoded, because what Blosc makes of a garbled frame depends
    on the memory beside it (a CI run once got KeyError: 4 from the text below, whose
    header asks for 1.7 GB); the last three have a header that matches the file."""
    return [
        ("text whose header asks for 1.7 GB", b"\x00garbage" * 3),
        ("no bytes", b""),
        *[(f"{n} random bytes, seed {seed}", np.random.default_rng(seed).integers(
            0, 256, n, dtype=np.uint8).tobytes()) for seed, n in ((1, 7), (2, 32), (3, 200))],
        ("its block's start beyond the file",
         _blosc_header(want, 40) + (1000).to_bytes(4, "little") + bytes(20)),
        ("a copied chunk's data cut short",
         _blosc_header(want, 16 + want // 2, flags=0x03) + bytes(want // 2)),
        ("a block size of 0", _blosc_header(want, 40, blocksize=0) + bytes(24)),
    ]


ROUND3 = [(f"{fn}: k = {k!r}", (lambda fn=fn, k=k: _public_k_functions()[fn](k)),
           (E, exc, r"\bk\b.*must be")) for fn in _public_k_functions() for k, exc in BAD_K]

ROUND3 += [
    # class 5: an overflow or underflow is told apart from a resonance
    ("nls_undefined: alpha 1e+250 overflows, not a resonance",
     lambda: _undefined(1e250, 0.024, 0.0205),
     ("ok", lambda why: why.startswith("an overflow in float64") and "not a resonance" in why)),
    ("nls_undefined: alpha 3e-280 underflows, not a resonance",
     lambda: _undefined(3e-280, 0.024, 0.0205),
     ("ok", lambda why: why.startswith("an underflow in float64") and "resonat" not in why)),
    ("nls_undefined: K_theta 5e307 overflows", lambda: _undefined(3.1, 0.024, 5e307),
     ("ok", lambda why: "float64" in why and "resonat" not in why)),
    ("point: --K-s 3e307 (omega overflows) is one line, no traceback",
     lambda: _cli("point", "--alpha", "3.1", "--K-s", "3e307", "--K-theta", "0.0205",
                  "--case", "coupled", "--k", "1.1"),
     (C, 2, r"not a positive float64 number .* not a resonance")),
    # class 5: advice names a real option of the command that gave it
    # 1e-8: above the smallest amplitude float64 resolves there (6.93e-9, probe 96)
    ("soliton: --amplitude 1e-8 --simulate: advice names --travel and --amplitude",
     lambda: _cli(*SOLITON, "--amplitude", "1e-8", "--simulate"),
     (C, 2, r"^(?!.*t_end).*take T = .*give --travel <= \S+, or --amplitude >= \S+")),
    # class 5: a --scheduler that no client here can use is one line naming it and the remedy
    ("map: --scheduler inproc://", lambda: _cli(*MAP, "--delta", "0.0035", "--k", "1.1",
                                                "--scheduler", "inproc://10.1.2.3/77/2"),
     (C, 2, r"--scheduler inproc://10.1.2.3/77/2: an inproc:// address .* give tcp://")),
    ("map: --scheduler ucx://", lambda: _cli(*MAP, "--delta", "0.0035", "--k", "1.1",
                                             "--scheduler", "ucx://127.0.0.1:9"),
     (C, 2, r"--scheduler ucx://127.0.0.1:9: cannot use it as a Dask scheduler")),
    # class 4: a damaged store is "damaged: NAME", repaired where the cells' data survive,
    # never "other parameters"; what xr.open_zarr reads first (.zmetadata) rebuilt
    *[(f"store: garbage in the delta coordinate's chunk ({what})",
       lambda data=data: _damaged_store(_write("delta/0", data)),
       ("ok", lambda r: len(r[0]) == 1 and "damaged: delta;" in r[0][0] and r[2]))
      for what, data in _garbage(16)],  # delta: 2 float64 in one chunk
    *[(f"store: garbage in a simulated column's chunk ({what})",
       lambda data=data: _damaged_store(_write("growth/1.0", data)),
       ("ok", lambda r: len(r[0]) == 1 and "1 of 4 cells" in r[0][0]
        and "delta = -0.002, k = 1.1" in r[0][0] and r[2]))
      for what, data in _garbage(8)],  # one float64 cell a chunk
    ("store: the k_simulated chunk deleted", lambda: _damaged_store(_remove("k_simulated/0")),
     ("ok", lambda r: len(r[0]) == 1 and "damaged: k_simulated;" in r[0][0] and r[2])),
    ("store: the K_theta .zarray deleted", lambda: _damaged_store(_remove("K_theta/.zarray")),
     ("ok", lambda r: len(r[0]) == 1 and "damaged: K_theta;" in r[0][0] and r[2])),
    ("store: a theory column's .zarray deleted", lambda: _damaged_store(
        _remove("peak_gain_semidiscrete/.zarray")),
     ("ok", lambda r: "damaged: peak_gain_semidiscrete;" in r[0][0] and r[2])),
    ("store: .zmetadata holds half a JSON", lambda: _damaged_store(
        _write(".zmetadata", b'{"metadata": {')),
     ("ok", lambda r: len(r[0]) == 1 and "damaged: .zmetadata;" in r[0][0] and r[2])),
    ("store: .zmetadata deleted", lambda: _damaged_store(_remove(".zmetadata")),
     ("ok", lambda r: len(r[0]) == 1 and "damaged: .zmetadata;" in r[0][0] and r[2])),
    ("store: .zattrs garbled: which map is unknown, named", lambda: _damaged_store(
        _write(".zattrs", b"\xff\xfe")),
     (E, ValueError, r"map.zarr: damaged: .zgroup/.zattrs .*--overwrite")),
    ("store: a simulated column's chunk garbled, the cell named and run again",
     lambda: _damaged_store(_write("growth/1.0", b"nonsense")),
     ("ok", lambda r: len(r[0]) == 1 and "1 of 4 cells" in r[0][0]
      and "delta = -0.002, k = 1.1" in r[0][0])),
    # class 4: a store of another map with no finished cell does not block
    ("store: another map with no finished cell is replaced", lambda: _damaged_store(
        lambda p: None, other=_params(N=160, theory_only=True)),
     ("ok", lambda r: len(r[0]) == 1 and "no finished cell" in r[0][0] and r[2])),
    ("store: another map with a finished cell is refused", lambda: _damaged_store(
        _mark_predicted, other=_params(N=160, theory_only=True)),
     (E, ValueError, r"holds a map with other parameters")),
    ("MapParameters: N 6 (no cell could run) is refused before any work",
     lambda: _params(N=6), (E, ValueError, r"N must be an integer in \[8, ")),
    # class 5: a lock file of any content is named with its path, never a traceback
    ("store lock: a live holder's record without 'since'", lambda: _lock(_record(
        host=__import__("socket").gethostname(), pid=__import__("os").getpid())),
     (E, ValueError, r"being written by pid \d+ on .* since an unknown time \(lock .*"
                     r"map.zarr.lock\)")),
    ("store lock: a binary lock file is replaced, named", lambda: _lock(
        lambda p: p.write_bytes(bytes(range(256)))),
     ("ok", lambda seen: len(seen) == 1 and "map.zarr.lock" in seen[0]
      and "no flexmm lock record" in seen[0])),
    ("store lock: a JSON list as lock file is replaced, named", lambda: _lock(
        lambda p: p.write_text("[1, 2]")),
     ("ok", lambda seen: len(seen) == 1 and "no flexmm lock record" in seen[0])),
    ("store lock: a folder where the lock file goes", lambda: _lock(lambda p: p.mkdir()),
     (E, ValueError, r"cannot read the lock file .*map.zarr.lock")),
    # class 2: every public numeric function refuses NaN, bool, complex, str and a bad sign
    # with the one set of checks (numerics.lattice.checks; generated code prints its rule)
    ("theory_gain: k NaN", lambda: _gain(math.nan), (E, ValueError, r"k must be in")),
    ("theory_gain: k False", lambda: _gain(False), (E, TypeError, r"k must be a real")),
    ("theory_gain: k 1.1+0j", lambda: _gain(1.1 + 0j), (E, TypeError, r"k must be a real")),
    ("theory_gain: k '1.1'", lambda: _gain("1.1"), (E, TypeError, r"k must be a real")),
    ("theory_gain: q_offset holds inf", lambda: _gain(1.1, (0.1, math.inf)),
     (E, ValueError, r"offset must hold finite")),
    ("theory_gain: q_offset complex", lambda: _gain(1.1, (0.1j,)),
     (E, TypeError, r"offset must hold real")),
    ("theory_gain: eps -0.01", lambda: _gain(1.1, eps=-0.01, A0=1.0),
     (E, ValueError, r"eps must be finite and > 0")),
    ("theory_gain: material a str", lambda: __import__("numerics").theory_gain(
        "paper NLS", "blue", "coupled", 1.1, offset=[0.1], amplitude=0.015),
     (E, TypeError, r"material must be a Material")),
    ("snap_wavenumber: N 0", lambda: _snap(N=0), (E, ValueError, r"N must be an integer in")),
    ("snap_wavenumber: N -64", lambda: _snap(N=-64), (E, ValueError, r"N must be an integer")),
    ("snap_wavenumber: N False", lambda: _snap(N=False), (E, TypeError, r"N must be an integer")),
    ("snap_wavenumber: N 120.0", lambda: _snap(N=120.0), (E, TypeError, r"N must be an integer")),
    ("snap_wavenumber: rel_tol NaN", lambda: _snap(rel_tol=math.nan),
     (E, ValueError, r"rel_tol must be >= 0 or None")),
    ("snap_wavenumber: rel_tol -0.1", lambda: _snap(rel_tol=-0.1), (E, ValueError, "rel_tol")),
    ("snap_wavenumber: rel_tol inf snaps anything", lambda: _snap(k=1.0, rel_tol=math.inf),
     ("ok", lambda r: abs(r - 2 * math.pi * 19 / 120) < 1e-15)),
    ("generated g1: k False", lambda: _generated("g1", False, 3.1, 0.024, 0.0205),
     (E, TypeError, r"k must hold real numbers")),
    ("generated omega: K_s '0.024'", lambda: _generated("omega", 1.1, 3.1, "0.024", 0.0205),
     (E, TypeError, r"K_s must hold real numbers")),
    ("generated g2_coupled: alpha 3.1j", lambda: _generated("g2_coupled", 1.1, 3.1j, 0.024,
                                                            0.0205),
     (E, TypeError, r"alpha must hold real numbers")),
    ("generated omega: integer arrays are real", lambda: _generated("omega", [1, 2], 3, 1, 1),
     ("ok", lambda w: w.shape == (2,) and bool(np.all(np.isfinite(w))))),
    # class 2: a run too short to show growth is refused (U's build-up from rest read as MI)
    ("map: --t-end 3e-5 (coupled) is too short to measure growth",
     lambda: _cli(*MAP, "--delta", "0.0035", "--k", "1.1", "--t-end", "3e-5"),
     (C, 2, r"--t-end = 3e-05 is too short to measure growth.*give at least \d+")),
    ("map: --t-end 40 (coupled) is too short to measure growth",
     lambda: _cli(*MAP, "--delta", "0.0035", "--k", "1.1", "--t-end", "40", "--theory-only"),
     (C, 2, r"--t-end = 40 is too short")),
    ("point: --t-end 2 --simulate is too short to measure growth",
     lambda: _cli(*POINT, "--simulate", "--t-end", "2"), (C, 2, r"--t-end = 2 is too short")),
    ("MapParameters: t_end 7 (coupled) is too short",
     lambda: _params(t_end=7.0), (E, ValueError, r"t_end = 7 is too short")),
    ("MapParameters: t_end 7 in case rotation (no U read) is accepted",
     lambda: _params(case="rotation", t_end=7.0), ("ok", lambda p: p.t_end == 7.0)),
    # class 2: a range whose count drops a bound
    ("parse_spec: 0.002:0.004:1 drops its stop", lambda: _spec("0.002:0.004:1"),
     (E, ValueError, r"--delta.*would drop 0.004")),
    ("map: --k 0.7:2.1:1 drops its stop",
     lambda: _cli(*MAP, "--delta", "0.0035", "--k", "0.7:2.1:1"), (C, 2, r"--k.*would drop 2.1")),
    ("parse_spec: 0.003:0.003:1 is one value", lambda: _spec("0.003:0.003:1"),
     ("ok", lambda v: v.tolist() == [0.003])),
    # class 2: an option that acts only with another is refused alone
    ("soliton: --travel 3 without --simulate", lambda: _cli(*SOLITON, "--travel", "3"),
     (C, 2, r"--travel does nothing without --simulate")),
    ("soliton: --N 400 without --simulate", lambda: _cli(*SOLITON, "--N", "400"),
     (C, 2, r"--N does nothing without --simulate")),
    # the paper chain's point predicts its growth per seed, no runs needed: --seeds acts
    # alone there; a model point's seeds are runs, so it is refused there
    ("point --model: --seeds 6 without --simulate", lambda: _cli(
        "point", "--model", "fput", "--k", "1.1", "--seeds", "6"),
     (C, 2, r"--seeds: a model point's seeds are its runs'")),
    # class 5: a negative non-finite value reaches the check that names its option
    ("map: --t-end -Infinity", lambda: _cli(*MAP, "--delta", "0.0035", "--k", "1.1",
                                            "--t-end", "-Infinity"), (C, 2, r"--t-end must be")),
    ("point: --amplitude -nan", lambda: _cli(*POINT, "--amplitude", "-nan"),
     (C, 2, r"--amplitude must be")),
    # class 5: a --out that is a link to nothing is named, with its target
    ("map: --out a dangling symbolic link", _dangling_out,
     (C, 2, r"out is a symbolic link to .*gone/away, which does not exist")),
    # class 5: a chain so small that U has no bin besides the carrier's harmonics
    ("point: --N 10 --simulate (U has no sideband bin) runs",
     lambda: _cli(*POINT, "--N", "10", "--simulate", "--seeds", "1", "--t-end", "400"),
     ("ok", lambda r: r == (0, ""))),
]
