"""A lattice model as data: fields, parameters and the energy of one unit cell.

The model file (TOML) is the contract; :class:`Lattice` is the same thing in Python. The
energy expressions are checked here with Python's own parser (:mod:`ast`), never evaluated:
only numbers, the declared names and a fixed list of elementary functions are allowed, so a
model file cannot run code. SymPy reads them later (``derivation``), from the checked tree.
"""

from __future__ import annotations

import ast
import builtins
import functools
import hashlib
import json
import keyword
import math
import numbers
import os
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType

from ._expressions import (  # the grammar; ModelError and its helpers live there too
    CONSTANTS,
    FUNCTIONS,
    MAX_CONSTANT,
    ModelError,
    _check_kinetic,
    _check_rayleigh,
    _checked_tree,
    _fail,
    _short,
)

# Letters and digits, single underscores between them. Unambiguous (each '_' starts a new
# group), so matching is linear in the name's length; the old ``(?:_?[A-Za-z0-9]+)*``
# backtracked exponentially on a long name ending in a character it refuses.
_NAME = re.compile(r"[A-Za-z][A-Za-z0-9]*(?:_[A-Za-z0-9]+)*")
#: The longest field or parameter name.
MAX_NAME = 64
#: Suffixes the generator gives a field (u_prev = u_{n-1}, u_next = u_{n+1}, u_t = du_n/dt):
#: no field or parameter may end in one.
_SUFFIXES = ("_next", "_prev", "_t")
#: Names the generated module uses itself (its imports, module constants and functions):
#: a field or parameter of the same name would shadow them.
GENERATOR_NAMES = frozenset({
    "numpy", "numba", "itertools", "math", "NAME", "FIELDS", "PARAMETERS", "MODEL_HASH",
    "BODY_SHA256", "SITE_FUNCTIONS_ALL", "masses", "cell_energy", "cell_gradient_into",
    "site_functions_all", "accelerations_into", "cell_hessian_into", "taylor",
    "damping_matrices"})
#: Every name a field or parameter may not take: Python's keywords and built-ins (the
#: generated code is Python), the generator's own names, the functions and constants.
RESERVED = frozenset(keyword.kwlist) | frozenset(keyword.softkwlist) | frozenset(
    n for n in dir(builtins) if not n.startswith("_")) | GENERATOR_NAMES
#: Bounds on what a model file may ask of the derivation (checked before SymPy sees it).
MAX_FILE_BYTES = 256 * 1024
MAX_TEXT = 4096  # description, references
MAX_FIELDS = 8
MAX_PARAMETERS = 64
MAX_VALUE = MAX_CONSTANT  # |a parameter's value|, |a carrier's amplitude|
_KEYS = {"name", "description", "fields", "parameters", "energy", "branch", "references",
         "dissipation"}
_ENERGY_KEYS = ("kinetic", "bond", "site")
#: Rayleigh dissipation functions (optional table [dissipation]): quadratic forms in the
#: velocities of cell n (``site``) and of cells n, n + 1 (``bond``), coefficients from the
#: parameters.
_DISSIPATION_KEYS = ("site", "bond")


def check_name(where: str, kind: str, name) -> str:
    """A field or parameter name: letters and digits with single '_' between them, at most
    MAX_NAME characters, not reserved (see :data:`RESERVED`) and not ending in a suffix the
    generator gives a field (_next, _prev, _t)."""
    if not isinstance(name, str):
        _fail(where, f"{kind} name must be a string, got {type(name).__name__} {_short(name)}")
    if len(name) > MAX_NAME:
        _fail(where, f"{kind} name {_short(name)} is longer than {MAX_NAME} characters")
    if not _NAME.fullmatch(name):
        _fail(where, f"{kind} name {_short(name)} is not valid (ASCII letters a-z, A-Z and "
                     "digits, single '_' between them, starting with a letter"
                     + (": spell a Greek letter out, 'theta' for '\u03b8')"
                        if not name.isascii() else ")"))
    if name.endswith(_SUFFIXES):
        _fail(where, f"{kind} name {name!r} ends in {name[name.rindex('_'):]!r}, which the "
                     "generator gives fields (u_prev, u_next, u_t): rename it")
    if name in FUNCTIONS or name in CONSTANTS:
        _fail(where, f"{kind} name {name!r} is a function or constant of the energies: "
                     "rename it")
    if name in RESERVED:
        why = ("a Python keyword" if keyword.iskeyword(name) or keyword.issoftkeyword(name)
               else "a name the generated code uses" if name in GENERATOR_NAMES
               else "a Python built-in")
        _fail(where, f"{kind} name {name!r} is reserved ({why}): rename it")
    return name


@dataclass(frozen=True)
class Lattice:
    """One lattice model: a periodic chain of identical unit cells with nearest-neighbour bonds.

    The energy per cell n is ``kinetic + bond + site`` where, for each field ``u``,
    ``u`` is u_n, ``u_next`` is u_{n+1} and ``u_t`` is du_n/dt. The kinetic energy is a
    diagonal positive quadratic form in the velocities, ``bond`` couples cell n to n + 1
    only, ``site`` depends on cell n only. The rest state (every field 0) must be an
    equilibrium. Equations of motion, dispersion, the NLS and the simulator's force all come
    from these three expressions (``derivation.model_energies``, ``compile_model``).

    Parameters
    ----------
    name : str
        Identifier (letters, digits, '-' and '_').
    fields : tuple of str
        Degrees of freedom per cell, in order.
    parameters : mapping str -> float
        Parameter names and their default values.
    kinetic, bond, site : str
        The energy expressions (Python/SymPy syntax, ``**`` for powers).
    description : str
        One line.
    branch : str or None
        The field whose branch commands use by default (None: the lowest branch).
    references : str
        Where the model comes from.
    source : str
        Where it was read from (a path, ``builtin:NAME`` or ``python``).
    """

    name: str
    fields: tuple
    parameters: MappingProxyType
    kinetic: str
    bond: str
    site: str = "0"
    description: str = ""
    branch: str | None = None
    references: str = ""
    source: str = "python"
    dissipation: MappingProxyType | None = None
    _trees: dict = field(default_factory=dict, repr=False, compare=False, hash=False)

    def __post_init__(self):
        where = f"model {self.name!r}" if isinstance(self.name, str) else "model"
        if not isinstance(self.name, str) or len(self.name) > MAX_NAME or not re.fullmatch(
                r"[A-Za-z][A-Za-z0-9_-]*", self.name):
            where = "model"
            _fail(where, f"name must be ASCII letters, digits, '-' or '_', starting with a "
                         f"letter (at most {MAX_NAME}), got {_short(self.name)}")
        for key in ("description", "references", "source"):
            text = getattr(self, key)
            if not isinstance(text, str):
                _fail(where, f"{key} must be a string, got {type(text).__name__} "
                             f"{_short(text)}")
            if key != "source" and len(text) > MAX_TEXT:
                _fail(where, f"{key} is {len(text)} characters long (at most {MAX_TEXT})")
        flds = self.fields
        if isinstance(flds, str) or not isinstance(flds, (list, tuple)) or not flds:
            _fail(where, f"fields must be a non-empty list of names, got {_short(flds)}")
        if len(flds) > MAX_FIELDS:
            _fail(where, f"{len(flds)} fields: at most {MAX_FIELDS} (the derivation's fourth-"
                         "order tensors grow as the fourth power of the fields)")
        for f in flds:
            check_name(where, "field", f)
        if len(set(flds)) != len(flds):
            _fail(where, f"fields repeat a name: {list(flds)}")
        object.__setattr__(self, "fields", tuple(flds))
        if not isinstance(self.parameters, (dict, MappingProxyType)):
            _fail(where, "parameters must be a mapping of name to default value, got "
                         f"{type(self.parameters).__name__}")
        params = dict(self.parameters)
        if len(params) > MAX_PARAMETERS:
            _fail(where, f"{len(params)} parameters: at most {MAX_PARAMETERS}")
        for p, v in params.items():
            check_name(where, "parameter", p)
            if p in flds:
                _fail(where, f"parameter {p!r} clashes with the field of the same name")
            params[p] = check_value(f"{where}: parameter {p}", v)
        object.__setattr__(self, "parameters", MappingProxyType(params))
        for key in _ENERGY_KEYS:
            text = getattr(self, key)
            if not isinstance(text, str) or not text.strip():
                _fail(where, f"energy.{key} must be an expression (a string), got {text!r}")
            self._trees[key] = _checked_tree(f"{where}: energy.{key}", text,
                                             self._allowed(key))
        if self.branch is not None and self.branch not in flds:
            _fail(where, f"branch {_short(self.branch, 40)} is not one of the fields "
                         f"{list(flds)}")
        _check_kinetic(where, self._trees["kinetic"], self.fields)
        self._check_dissipation(where)

    def _check_dissipation(self, where: str):
        diss = self.dissipation
        if diss is None:
            return
        if not isinstance(diss, (dict, MappingProxyType)):
            _fail(where, "[dissipation] must be a table with site and/or bond, got "
                         f"{type(diss).__name__}")
        extra = sorted(str(k) for k in set(diss) - set(_DISSIPATION_KEYS))
        if extra:
            _fail(where, f"unknown dissipation key(s) {', '.join(extra)} (known: site, bond)")
        if not diss:
            _fail(where, "[dissipation] is empty: give site and/or bond (or leave it out)")
        out = {}
        for key in _DISSIPATION_KEYS:
            if key not in diss:
                continue
            text = diss[key]
            if not isinstance(text, str) or not text.strip():
                _fail(where, f"dissipation.{key} must be an expression (a string), got "
                             f"{_short(text)}")
            tree = _checked_tree(f"{where}: dissipation.{key}", text,
                                 self._allowed("dissipation." + key))
            _check_rayleigh(f"{where}: dissipation.{key}", tree)
            self._trees["dissipation." + key] = tree
            out[key] = text
        object.__setattr__(self, "dissipation", MappingProxyType(out))

    def _allowed(self, key: str) -> set:
        names = set(self.parameters) | set(FUNCTIONS) | set(CONSTANTS)
        if key.startswith("dissipation."):  # velocities and parameters only
            names |= {f + "_t" for f in self.fields}
            if key == "dissipation.bond":
                names |= {f + "_next_t" for f in self.fields}
            return names
        if key == "kinetic":
            return names | {f + "_t" for f in self.fields}
        names |= set(self.fields)
        if key == "bond":
            names |= {f + "_next" for f in self.fields}
        return names

    @property
    def n_fields(self) -> int:
        return len(self.fields)

    def tree(self, key: str) -> ast.Expression:
        """The checked syntax tree of energy ``key`` (kinetic, bond or site) or of a
        dissipation function (``dissipation.site``, ``dissipation.bond``)."""
        return self._trees[key]

    @property
    def lossy(self) -> bool:
        """Whether the model has a [dissipation] table."""
        return self.dissipation is not None

    def canonical(self) -> dict:
        """What defines the equations (not the defaults, the description or the source).
        A model without [dissipation] has no key for it: its hash is the lossless one."""
        out = {"name": self.name, "fields": list(self.fields),
               "parameters": sorted(self.parameters),
               "energy": {k: ast.dump(self._trees[k]) for k in _ENERGY_KEYS}}
        if self.dissipation is not None:
            out["dissipation"] = {k: ast.dump(self._trees["dissipation." + k])
                                  for k in self.dissipation}
        return out

    @functools.cached_property
    def content_hash(self) -> str:
        """sha256 of :meth:`canonical`: the key of the derived code's cache (computed once
        per object: a frozen Lattice's content does not change; ~0.3 ms a call, asked per
        map cell and per theory)."""
        text = json.dumps(self.canonical(), sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()

    def with_energy(self, **changes) -> Lattice:
        """A copy with some of name, fields, parameters, kinetic, bond, site replaced."""
        kw = {k: getattr(self, k) for k in ("name", "fields", "parameters", "kinetic", "bond",
                                           "site", "description", "branch", "references",
                                           "source", "dissipation")}
        unknown = sorted(set(changes) - set(kw))
        if unknown:  # before: dataclass's TypeError "__init__() got an unexpected keyword"
            raise ModelError(f"model {self.name!r}: with_energy cannot replace "
                             f"{', '.join(unknown)} (it replaces: {', '.join(kw)})")
        kw.update(changes)
        return Lattice(**kw)

    def values(self, params: dict | None = None) -> dict:
        """Defaults overridden by ``params`` (unknown names refused, values checked)."""
        out = dict(self.parameters)
        for p, v in (params or {}).items():
            if p not in out:
                raise ModelError(f"model {self.name!r} has no parameter {p!r} (it has: "
                                 f"{', '.join(self.parameters) or 'none'})")
            out[p] = check_value(f"parameter {p}", v)
        return out


def check_value(where: str, v) -> float:
    """A parameter value (or a carrier's amplitude): a finite real number (not a bool, a
    string or a complex) of size at most ``MAX_VALUE``, the bound on a number in an energy
    (beyond it a coefficient's powers overflow: g2 of FPUT at alpha = 1e100 is inf)."""
    if getattr(v, "ndim", None) == 0 and getattr(getattr(v, "dtype", None), "kind", "") \
            in "fiu" and not isinstance(v, numbers.Number):
        v = v.item()  # a 0-d real array is the number it holds (probe 99)
    if isinstance(v, bool) or not isinstance(v, numbers.Real):
        raise ModelError(f"{where} must be a real number, got {type(v).__name__} {v!r}")
    v = float(v)
    if not math.isfinite(v):
        raise ModelError(f"{where} must be finite, got {v!r}")
    if abs(v) > MAX_VALUE:
        raise ModelError(f"{where} must be at most {MAX_VALUE:g} in size (a model's numbers "
                         f"are bounded so that its coefficients stay finite: rescale its "
                         f"units), got {v!r}")
    return v


def read_model(path: str | Path) -> Lattice:
    """Read a model file (TOML): the format of ``docs/models.md``."""
    if not isinstance(path, (str, os.PathLike)):
        raise ModelError(f"read_model: the path of a model file (.toml) must be a str or "
                         f"os.PathLike, got {type(path).__name__} {path!r}")
    path = Path(path)
    where = str(path)
    try:
        if not path.is_file():
            raise ModelError(f"{where}: no such model file" if not path.exists() else
                             f"{where}: not a regular file (a model file is a .toml file)")
        with path.open("rb") as fh:
            raw = fh.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise ModelError(f"{where}: cannot read the model file ({exc.strerror or exc})") \
            from None
    if len(raw) > MAX_FILE_BYTES:
        raise ModelError(f"{where}: the model file is larger than {MAX_FILE_BYTES // 1024} KiB")
    try:
        text = raw.decode("utf-8-sig")  # a byte-order mark (Windows editors) is no TOML
    except UnicodeDecodeError as exc:
        raise ModelError(f"{where}: the model file is not UTF-8 text (byte {exc.start})") \
            from None
    return parse_model(text, where)


def _bare_key_hint(text: str, exc) -> str:
    """A hint where the failing line's key holds a non-ASCII letter (``ω0 = 1.0``: TOML's
    own message, 'Invalid statement', names no cause)."""
    import re

    found = re.search(r"at line (\d+)", str(exc))  # tomllib's message (3.11-3.13)
    line = int(found.group(1)) if found else None
    lines = text.removeprefix("\ufeff").splitlines()
    if not line or line > len(lines):
        return ""
    key = lines[line - 1].split("=", 1)[0].strip()
    if not key or key.isascii() or key.startswith(("\"", "'", "#", "[")):
        return ""
    return (f"; the key {key!r} is not ASCII: model names are ASCII letters, digits and '_' "
            "(spell a Greek letter out, 'omega0' for 'ω0')")


def parse_model(text: str, where: str = "model") -> Lattice:
    """A :class:`Lattice` from the text of a model file."""
    if not isinstance(text, str):
        raise ModelError(f"{where}: the model's text must be a string, got "
                         f"{type(text).__name__}")
    if len(text.encode("utf-8", "surrogatepass")) > MAX_FILE_BYTES:
        raise ModelError(f"{where}: the model file is larger than {MAX_FILE_BYTES // 1024} KiB")
    try:
        data = tomllib.loads(text.removeprefix("\ufeff"))  # a byte-order mark: no TOML
    except tomllib.TOMLDecodeError as exc:
        raise ModelError(f"{where}: not valid TOML ({_short(exc, 200)[1:-1]})"
                         f"{_bare_key_hint(text, exc)}") from None
    except (RecursionError, MemoryError):
        raise ModelError(f"{where}: not valid TOML (nested too deeply)") from None
    unknown = sorted(set(data) - _KEYS)
    if unknown:
        _fail(where, f"unknown key(s) {', '.join(unknown)} (known: {', '.join(sorted(_KEYS))})")
    for key in ("name", "fields", "energy"):
        if key not in data:
            _fail(where, f"missing key {key!r}")
    energy = data["energy"]
    if not isinstance(energy, dict):
        _fail(where, "[energy] must be a table with kinetic, bond and site")
    extra = sorted(set(energy) - set(_ENERGY_KEYS))
    if extra:
        _fail(where, f"unknown energy key(s) {', '.join(extra)} (known: kinetic, bond, site)")
    for key in ("kinetic", "bond"):
        if key not in energy:
            _fail(where, f"missing energy.{key}")
    params = data.get("parameters", {})
    if not isinstance(params, dict):
        _fail(where, "[parameters] must be a table of name = default value")
    try:
        return Lattice(name=data["name"], fields=data["fields"], parameters=params,
                       kinetic=energy["kinetic"], bond=energy["bond"],
                       site=energy.get("site", "0"),
                       description=data.get("description", ""),
                       branch=data.get("branch"), references=data.get("references", ""),
                       source=where, dissipation=data.get("dissipation"))
    except ModelError as exc:
        msg = str(exc)
        raise ModelError(msg if msg.startswith(where) else f"{where}: {msg}") from None
