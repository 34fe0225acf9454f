"""Running scenes: the context a scene computes in, its files, the report.

``run_scene`` writes ``OUT/NAME/{data.h5, figure.png, figure.pdf, summary.json}``, each
atomically (complete or absent); ``replot_scene`` redraws the figure from ``data.h5``
alone; ``run_all`` runs every scene and writes ``OUT/report.md``.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path

import h5py
import numpy as np

from common.files import atomic_write, umask, write_text
from common.output import prepare_output, strict_json
from numerics import SIMULATOR_VERSION
from numerics.lattice import cached_simulate, checks

from ._plotting import plt
from ._registry import REGISTRY, get_scene


def package_version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("flexmm-mi")
    except PackageNotFoundError:  # pragma: no cover
        return "unknown"


@dataclass
class Context:
    """What a scene may use: quick or not, the seed, and simulations through the cache."""

    quick: bool = False
    seed: int = 0
    force: bool = False
    cache_dir: Path | None = None

    def simulate(self, **params):
        """``numerics.simulate(**params)`` through the on-disk cache."""
        params.setdefault("progress", None)
        return cached_simulate(self.cache_dir, self.force, **params)

    def progress(self, items, desc: str):
        """``items`` with a progress bar (tqdm) on a terminal, silent when stderr is not
        one: the steps of a scene that can pass 10 s."""
        from common.progress import progress_class
        tqdm = progress_class()

        return tqdm(items, desc=desc, leave=False, disable=None, unit="step")

    def memo(self, tag: str, params: dict, compute):
        """``compute()`` (an array, or JSON-able data) cached under ``tag`` and ``params``
        (plain values) and the simulator's source hash: theory work is not redone."""
        if self.cache_dir is None:
            return compute()
        blob = json.dumps({"tag": tag, "params": params, "code": SIMULATOR_VERSION},
                          sort_keys=True, default=_jsonable)
        key = hashlib.sha256(blob.encode()).hexdigest()[:24]
        npy, js = self.cache_dir / f"{tag}-{key}.npy", self.cache_dir / f"{tag}-{key}.json"
        if not self.force:
            try:
                if npy.exists():
                    return np.load(npy)
                if js.exists():
                    return json.loads(js.read_text())
            except (OSError, ValueError):
                pass  # unreadable: recompute
        value = compute()
        self.cache_dir.mkdir(parents=True, exist_ok=True)
        if isinstance(value, np.ndarray):
            with atomic_write(npy, "wb") as fh:
                np.save(fh, value)
        else:
            write_text(js, json.dumps(value, default=_jsonable))
        return value


# --- data.h5: arrays as datasets, everything else as attributes -------------------------

def _is_array(v):
    return isinstance(v, np.ndarray) and v.dtype.kind in "fcib"


def write_data(path: Path, data: dict):
    """Arrays become datasets (a "/" in a name makes groups); other values attributes,
    native when int/float/str/bool, JSON otherwise (their names listed in ``_json``)."""
    encoded = []
    with atomic_write(path, mode=None) as tmp, h5py.File(tmp, "w") as f:
        for name, val in data.items():
            if val is None:
                continue
            if _is_array(val):
                f.create_dataset(name, data=val)
            elif isinstance(val, (bool, int, float, str, np.bool_, np.integer, np.floating)):
                f.attrs[name] = val
            else:
                f.attrs[name] = json.dumps(val, sort_keys=True, default=_jsonable)
                encoded.append(name)
        f.attrs["_json"] = json.dumps(sorted(encoded))


def read_data(path: Path) -> dict:
    """The ``data`` dict a scene's ``compute`` returned, from its ``data.h5``."""
    out = {}
    with h5py.File(path, "r") as f:
        encoded = set(json.loads(f.attrs.get("_json", "[]")))
        f.visititems(lambda name, obj: out.__setitem__(name, obj[()])
                     if isinstance(obj, h5py.Dataset) else None)
        for name, val in f.attrs.items():
            if name == "_json":
                continue
            val = val.item() if hasattr(val, "item") else val
            out[name] = json.loads(val) if name in encoded else val
    return out


def _jsonable(x):
    if isinstance(x, (np.floating, np.integer)):
        return x.item()
    if isinstance(x, np.bool_):
        return bool(x)
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, tuple):
        return list(x)
    raise TypeError(type(x))


def _save_figure(fig, folder: Path, quick: bool):
    if quick:
        fig.text(0.99, 0.005, "QUICK MODE (reduced N / t_end / grid)", ha="right",
                 va="bottom", fontsize=7, color="red")
    for ext, kw in (("png", {"dpi": 110}), ("pdf", {})):
        with atomic_write(folder / f"figure.{ext}", mode=None) as tmp:
            fig.savefig(tmp, format=ext, **kw)
    plt.close(fig)


def _publish(tmp: Path, folder: Path):
    """Replace ``folder`` by the complete ``tmp`` folder: the scene's files change together
    (never a mix of two runs); a crash in between leaves the old or the new folder."""
    if folder.exists() and not folder.is_dir():
        raise ValueError(f"{folder} is a file, not a folder")
    old = folder.with_name(f".{folder.name}.old-{os.getpid()}")
    if folder.exists():
        os.replace(folder, old)
    os.replace(tmp, folder)
    shutil.rmtree(old, ignore_errors=True)


def run_scene(name: str, out: Path | str = "out", quick: bool = False, seed: int = 0,
              force: bool = False) -> dict:
    """Run one scene; writes OUT/NAME/{data.h5, figure.png, figure.pdf, summary.json}.

    The files are written into a hidden folder beside OUT/NAME and published together
    when all four are complete (an interrupted run leaves the previous ones untouched).
    """
    sc = get_scene(name)
    seed = checks.seed(seed)
    out = prepare_output(out)
    folder = out / name
    if folder.exists() and not folder.is_dir():
        raise ValueError(f"{folder} is a file, not a folder")
    ctx = Context(quick=quick, seed=seed, force=force, cache_dir=out / ".cache")
    data, summary = sc.compute(ctx)
    data = dict(data, scene=name, seed=seed, quick=quick, package_version=package_version())
    summary = {"scene": name, **summary, "seed": seed, "quick": quick,
               "package_version": package_version()}
    tmp = Path(tempfile.mkdtemp(prefix=f".{name}.partial-", dir=out))
    try:
        write_data(tmp / "data.h5", data)
        _save_figure(sc.plot(data), tmp, quick)
        write_text(tmp / "summary.json",
                   json.dumps(strict_json(summary), indent=2, allow_nan=False) + "\n")
        os.chmod(tmp, 0o777 & ~umask())
        _publish(tmp, folder)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return summary


def replot_scene(name: str, out: Path | str = "out") -> Path:
    """Redraw OUT/NAME/figure.{png,pdf} from OUT/NAME/data.h5, computing nothing."""
    sc = get_scene(name)
    folder = Path(out) / name
    path = folder / "data.h5"
    if not path.is_file():
        raise ValueError(f"{path} does not exist: run `flexmm scene {name}` first")
    redo = f"run `flexmm scene {name} --out {out}` to compute it again"
    try:
        data = read_data(path)
    except (OSError, KeyError, ValueError) as exc:  # not HDF5, truncated, torn
        raise ValueError(f"{path} cannot be read ({_first_line(exc)}): {redo}") from None
    try:
        fig = sc.plot(data)
    except KeyError as exc:  # a dataset the figure needs is missing
        raise ValueError(f"{path} lacks the dataset {exc.args[0]!r} the figure needs: "
                         f"{redo}") from None
    _save_figure(fig, folder, bool(data.get("quick")))
    return folder


def _first_line(exc) -> str:
    text = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    return text[:160]


def _pct(x):
    return "n/a" if x is None or not np.isfinite(x) else f"{100 * x:+.1f}%"


def write_report(summaries: dict, out: Path, quick: bool) -> Path:
    """OUT/report.md: one row per check (theory, numerics, outcome), then the findings
    that were expected, anything unexpected, and each scene's own section."""
    lines = ["# Theory versus numerics", "",
             f"Mode: {'quick (reduced N / t_end / grids; see each figure)' if quick else 'full'}."
             f" Package {package_version()}.", "",
             "Outcome: *agrees*; *paper disagrees (...)*: a known disagreement with the paper "
             "(erratum or a finding in docs/), as expected; anything unexpected is marked in bold "
             "and listed under \"Unexpected results\" (none: no such section).", "",
             "| scene | check | theory | numerics | outcome |", "|---|---|---|---|---|"]
    failed = []
    for name, s in summaries.items():
        for c in s.get("checks", []):
            shown = c["outcome"] if c["pass"] else f"**{c['outcome']}**"
            if not c["pass"]:
                failed.append((name, c))
            lines.append(f"| {name} | {c['check']} | {c['theory']} | {c['numerics']} | {shown} |")
    lines.append("")
    if failed:
        lines.append("## Unexpected results")
        for name, c in failed:
            lines.append(f"- **{name}** - {c['check']}: theory {c['theory']}, numerics "
                         f"{c['numerics']} ({c['outcome']}).")
    else:
        lines.append("Every check came out as expected: agreement, or a known disagreement "
                     "with the paper.")
    for name, s in summaries.items():
        sc = REGISTRY.get(name)
        if sc is not None and sc.report is not None:
            lines += [""] + sc.report(s)
    return write_text(Path(out) / "report.md", "\n".join(lines) + "\n")


def run_all(out="out", quick=False, seed=0, force=False, names=None, log=None) -> Path:
    """Run every scene (or ``names``) and write OUT/report.md; ``log(line)`` hears of each
    scene as it finishes (its time and check outcomes), so a long run shows progress also
    when its output goes to a file."""
    import time

    out = prepare_output(out)
    names = list(names or REGISTRY)
    summaries = {}
    for i, name in enumerate(names, 1):
        t0 = time.perf_counter()
        summaries[name] = run_scene(name, out, quick, seed, force)
        if log is not None:
            outcomes = [c["outcome"] for c in summaries[name].get("checks", [])]
            counts = ", ".join(f"{outcomes.count(o)} {o}" for o in sorted(set(outcomes)))
            log(f"[{i}/{len(names)}] {name}: {time.perf_counter() - t0:.1f} s"
                + (f" ({counts})" if counts else ""))
    return write_report(summaries, Path(out), quick)
