"""Built-in models, model lookup, and a model joined to its values and generated code."""

from __future__ import annotations

import functools
import hashlib
import importlib
import importlib.util
import os
import sys
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType, ModuleType

from ._spec import Lattice, ModelError, parse_model, read_model

MODELS_DIR = Path(__file__).with_name("models")
#: Names of the built-in models (energy/models/NAME.toml).
BUILTIN = tuple(sorted(p.stem for p in MODELS_DIR.glob("*.toml")))


def builtin(name: str) -> Lattice:
    """The built-in model ``name`` (one of :data:`BUILTIN`)."""
    if name not in BUILTIN:
        raise ModelError(f"no built-in model {name!r}; built-in: {', '.join(BUILTIN)} "
                         "(or give a path to a .toml model file)")
    lat = read_model(MODELS_DIR / f"{name}.toml")
    return lat.with_energy(source=f"builtin:{name}")


def resolve_model(model) -> Lattice:
    """A :class:`Lattice` from a Lattice, a built-in name, a path to a model file or a
    model file's text (a string of several lines: no name or path has a line break)."""
    if isinstance(model, Lattice):
        return model
    if isinstance(model, str) and "\n" in model:
        return parse_model(model, where="model text")
    if isinstance(model, os.PathLike) or (isinstance(model, str) and (
            model.endswith(".toml") or os.sep in model)):
        return read_model(model)
    if isinstance(model, str):
        return builtin(model)
    raise ModelError(f"model must be a built-in name, a .toml path, a model file's text or a "
                     f"Lattice, got "
                     f"{type(model).__name__} {model!r}")


def module_name(name: str) -> str:
    """Python module name of a built-in model's generated code (generated/models/)."""
    return name.replace("-", "_")


#: The layout of a generated model module (its functions and their arguments); a cached
#: module of another layout is derived again (2: the site loop accelerations_into, argument
#: names that no field or parameter can shadow; 3: no text of the model file but checked
#: names and repr literals, and a last line holding the hash of the body; 4: the force loop
#: over the bonds, each bond's pulls computed once, the ring's ends outside the loop;
#: 5: a derivative at rest that SymPy's simplify splits into a Piecewise with an infinite
#: branch at a special parameter value is printed unsimplified, not as nan, probe 97).
CODEGEN_VERSION = 5

#: The last line of a generated model module: sha256 of everything before it.
BODY_HASH_PREFIX = "# BODY_SHA256 = "


class ModelCacheWarning(UserWarning):
    """The derived code of a model in the cache was damaged and is derived again."""


def body_hash(text: str) -> str:
    """sha256 of a generated module's body (its text before the hash line)."""
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def with_body_hash(text: str) -> str:
    """``text`` (ending in a newline) with its hash line appended."""
    return f"{text}{BODY_HASH_PREFIX}{body_hash(text)}\n"


def check_generated(path: Path, model_hash: str) -> str | None:
    """What is wrong with the generated module at ``path`` for a model of content hash
    ``model_hash`` (None: it is whole). Read as bytes and checked before anything imports
    it: UTF-8, a last line holding the hash of the body, the body's MODEL_HASH."""
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        return "missing"
    except OSError as exc:
        return f"unreadable ({exc.strerror or exc})"
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        return "not UTF-8 text"
    body, sep, last = text.rstrip("\n").rpartition("\n")
    if not sep or not last.startswith(BODY_HASH_PREFIX):
        return "no hash line (truncated, or of an older layout)"
    if last[len(BODY_HASH_PREFIX):].strip() != body_hash(body + "\n"):
        return "its body does not match its hash line: edited?"
    if f"\nMODEL_HASH = {model_hash!r}\n" not in body:
        return "derived from another energy"
    return None


def cache_dir() -> Path:
    """Where derived code of models that are not built in is kept (FLEXMM_CACHE or
    ~/.cache/flexmm-mi/models), one file per content hash."""
    root = os.environ.get("FLEXMM_CACHE")
    return Path(root) if root else Path.home() / ".cache" / "flexmm-mi" / "models"


def _import_file(path: Path, name: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod  # numba's cache locates a function's module through sys.modules
    try:
        spec.loader.exec_module(mod)
    except BaseException:
        sys.modules.pop(name, None)
        raise
    return mod


def _builtin_code(lat: Lattice, h: str) -> ModuleType | None:
    """The committed generated module of a built-in model, when it is whole and of this
    energy (checked before it is imported)."""
    name = f"generated.models.{module_name(lat.name)}"
    if name in sys.modules:
        mod = sys.modules[name]
        return mod if getattr(mod, "MODEL_HASH", None) == h else None
    try:
        spec = importlib.util.find_spec(name)
    except (ImportError, ValueError):
        return None
    if spec is None or spec.origin is None or check_generated(Path(spec.origin), h):
        return None
    try:
        mod = importlib.import_module(name)
    except ImportError:
        return None
    return mod if getattr(mod, "MODEL_HASH", None) == h else None


def generated_code(lat: Lattice) -> ModuleType:
    """The generated module of ``lat``: the committed one of a built-in model, else the
    cached one, derived now if it is not cached (SymPy, seconds).

    A cached module is checked before it is imported (:func:`check_generated`): a damaged
    one is derived again, said in one :class:`ModelCacheWarning`. A module that does not
    import is removed from the cache and the model refused (:class:`ModelError`)."""
    h = lat.content_hash
    if lat.source.startswith("builtin:"):
        mod = _builtin_code(lat, h)
        if mod is not None:
            return mod
    path = cache_dir() / f"model_{h[:24]}_v{CODEGEN_VERSION}.py"
    name = f"_flexmm_model_{h[:24]}_v{CODEGEN_VERSION}"
    if name in sys.modules:
        return sys.modules[name]
    problem = check_generated(path, h)
    if problem is not None:
        if problem != "missing":
            import warnings

            warnings.warn(f"the cached code of model {lat.name!r} ({path}) is damaged "
                          f"({problem}): "
                          "derived again", ModelCacheWarning, stacklevel=2)
        from derivation import compile_model  # the one step that needs SymPy

        try:
            compile_model(lat, path)
        except OSError as exc:  # say which file could not be written
            raise OSError(exc.errno, f"cannot write the derived code of model {lat.name!r} "
                          f"({exc.strerror or exc})", str(path)) from None
        problem = check_generated(path, h)
        if problem is not None:  # another process wrote a different file meanwhile
            raise ModelError(f"model {lat.name!r}: its derived code at {path} is {problem} "
                             "right after it was written; remove the file and try again")
    try:
        return _import_file(path, name)
    except Exception as exc:  # never keep a module that does not import
        try:
            path.unlink()
        except OSError:
            pass
        raise ModelError(f"model {lat.name!r}: its generated code does not import "
                         f"({type(exc).__name__}: {str(exc).splitlines()[0][:200] if str(exc) else ''}); "
                         "this is a bug of the generator, please report it with the model "
                         "file") from None


@dataclass(frozen=True)
class Model:
    """A lattice model with parameter values and its generated code: what numerics takes.

    Attributes
    ----------
    lattice : Lattice
        The model (fields, energies).
    params : mapping str -> float
        Every parameter's value (defaults overridden).
    code : module
        The generated derivatives of the cell energy (``generated/models`` or the cache).
    """

    lattice: Lattice
    params: MappingProxyType
    code: ModuleType

    @property
    def name(self) -> str:
        return self.lattice.name

    @property
    def fields(self) -> tuple:
        return self.lattice.fields

    @property
    def n_fields(self) -> int:
        return self.lattice.n_fields

    @property
    def p(self):
        """Parameter values as a float array in the generated code's order (its
        ``PARAMETERS``): two files that differ only in the order of their parameters share
        one content hash, and so one cached module, derived from whichever came first
        (probe 100: a file with ``gamma`` declared before ``K_b`` ran on another's module
        with the two values swapped, its damping 25x and its bending stiffness 25x off)."""
        import numpy as np

        order = getattr(self.code, "PARAMETERS", None) or self.lattice.parameters
        return np.array([self.params[k] for k in order], dtype=float)

    @property
    def masses(self):
        import numpy as np

        m = np.asarray(self.code.masses(self.p), dtype=float)
        bad = [f for f, v in zip(self.fields, m) if not (np.isfinite(v) and v > 0)]
        if bad:
            import re

            # the parameters the kinetic energy holds are the ones to change (the remedy)
            used = [p for p in self.lattice.parameters
                    if re.search(rf"\b{p}\b", self.lattice.kinetic)]
            raise ModelError(f"model {self.name!r}: the mass of {', '.join(bad)} is not > 0 "
                             f"at {self.describe()} (masses {m.tolist()}, from kinetic = "
                             f"{self.lattice.kinetic!r})"
                             + (f": change {', '.join(f'--param {p}' for p in used)}"
                                if used else ": give each velocity a positive mass"))
        return m

    @functools.cached_property
    def lossy(self) -> bool:
        """Whether the model damps anything at these values: a [dissipation] table whose
        Rayleigh function is not zero here (probe 100: ``flexmm-lossy`` at gamma_theta =
        gamma_U = 0 printed a carrier damping of 0 and an unbounded amplification, where
        the lossless answer is the whole story). ``lattice.lossy`` says whether the file
        has the table (a map over a damping axis from 0 is a lossy map)."""
        if not self.lattice.lossy:
            return False
        import numpy as np

        return any(bool(np.any(C != 0)) for C in self.damping)

    @property
    def damping(self):
        """(C_site (d, d), C_bond (2 d, 2 d)): the Hessians of the Rayleigh functions in the
        velocities at these values (zeros without [dissipation]), checked symmetric
        positive semi-definite: R >= 0 for every velocity of the chain."""
        import numpy as np

        d = self.n_fields
        if not self.lattice.lossy:
            return np.zeros((d, d)), np.zeros((2 * d, 2 * d))
        if not hasattr(self.code, "damping_matrices"):
            raise ModelError(f"model {self.name!r}: its generated module has no damping "
                             "(an older layout): run `make derive`")
        S, B = (np.asarray(x, dtype=float) for x in self.code.damping_matrices(self.p))
        for key, C in (("site", S), ("bond", B)):
            if not np.all(np.isfinite(C)):
                raise ModelError(f"model {self.name!r}: dissipation.{key} is not finite at "
                                 f"{self.describe()}")
            lam = np.linalg.eigvalsh((C + C.T) / 2) if C.size else np.zeros(1)
            scale = max(1.0, float(np.max(np.abs(C))))
            if lam[0] < -1e-12 * scale:
                raise ModelError(f"model {self.name!r}: dissipation.{key} is not positive "
                                 f"semi-definite at {self.describe()} (an eigenvalue of its "
                                 f"velocity Hessian is {lam[0]:.3g} < 0): R must be >= 0")
        return S, B

    def with_params(self, **params) -> Model:
        """The same model at other parameter values."""
        checked = self.lattice.values(params)
        vals = dict(self.params)
        vals.update({p: checked[p] for p in params})
        out = Model(self.lattice, MappingProxyType(vals), self.code)
        if out.lattice.lossy:
            out.damping  # noqa: B018 (checks R >= 0 at the new values)
        return out

    def describe(self) -> str:
        """``name (p1 = v1, p2 = v2)``: the full model in one line (titles, tables)."""
        vals = ", ".join(f"{k} = {v:g}" for k, v in self.params.items())
        return f"{self.name} ({vals})" if vals else self.name

    def key(self) -> str:
        """Content hash of the energy and the values (store and cache keys)."""
        text = self.lattice.content_hash + repr(sorted(self.params.items()))
        return hashlib.sha256(text.encode()).hexdigest()


def load_model(model, **params) -> Model:
    """A :class:`Model` from a built-in name, a model file or a :class:`Lattice`.

    Parameters
    ----------
    model : str, path or Lattice
        ``"fput"``, ``"my_chain.toml"``, ..., or the text of a model file (a string of
        several lines, as :func:`parse_model` reads it).
    **params : float
        Parameter values; the others keep the model's defaults.

    Examples
    --------
    >>> from energy import load_model
    >>> load_model("fput", beta=2.0).describe()
    'fput (alpha = 0, beta = 2)'
    """
    lat = resolve_model(model)
    vals = lat.values(params)
    out = Model(lat, MappingProxyType(vals), generated_code(lat))
    if lat.lossy:
        out.damping  # noqa: B018 (checks R >= 0 at these values)
    return out
