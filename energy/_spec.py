"""A lattice model as data: fields, parameters and the energy of one unit cell.

The model file (TOML) is the contract; :class:`Lattice` is the same thing in Python. The
energy expressions are checked here with Python's own parser (:mod:`ast`), never evaluated:
only numbers, the declared names and a fixed list of elementary functions are allowed, so a
model file cannot run code. SymPy reads them later (``derivation``), from the checked tree.
"""

from __future__ import annotations

import ast
import hashlib
import json
import math
import numbers
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType

#: Elementary functions an energy may call (SymPy names).
FUNCTIONS = ("sin", "cos", "tan", "exp", "log", "sqrt", "sinh", "cosh", "tanh", "atan",
             "Abs")
#: Constants an energy may use.
CONSTANTS = ("pi",)
_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9]*(?:_?[A-Za-z0-9]+)*$")
_SUFFIXES = ("_next", "_t")
_KEYS = {"name", "description", "fields", "parameters", "energy", "branch", "references"}
_ENERGY_KEYS = ("kinetic", "bond", "site")


class ModelError(ValueError):
    """A model that cannot be used, with one line that says why and where."""


def _fail(where: str, message: str):
    raise ModelError(f"{where}: {message}")


@dataclass(frozen=True)
class Lattice:
    """One lattice model: a periodic chain of identical unit cells with nearest-neighbour bonds.

    The energy per cell n is ``kinetic + bond + site`` where, for each field ``u``,
    ``u`` is u_n, ``u_next`` is u_{n+1} and ``u_t`` is du_n/dt. The kinetic energy is a
    diagonal positive quadratic form in the velocities, ``bond`` couples cell n to n + 1
    only, ``site`` depends on cell n only. The rest state (every field 0) must be an
    equilibrium. Equations of motion, dispersion, the NLS and the simulator's force all come
    from these three expressions (``derivation.derive_model``).

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
    _trees: dict = field(default_factory=dict, repr=False, compare=False, hash=False)

    def __post_init__(self):
        where = f"model {self.name!r}" if isinstance(self.name, str) else "model"
        if not isinstance(self.name, str) or not re.fullmatch(r"[A-Za-z][A-Za-z0-9_-]*",
                                                              self.name):
            _fail(where, f"name must be letters, digits, '-' or '_', got {self.name!r}")
        flds = self.fields
        if isinstance(flds, str) or not isinstance(flds, (list, tuple)) or not flds:
            _fail(where, f"fields must be a non-empty list of names, got {flds!r}")
        for f in flds:
            if not isinstance(f, str) or not _NAME.match(f) or f.endswith(_SUFFIXES):
                _fail(where, f"field name {f!r} is not valid (letters and digits, not ending "
                             "in _next or _t)")
        if len(set(flds)) != len(flds):
            _fail(where, f"fields repeat a name: {list(flds)}")
        object.__setattr__(self, "fields", tuple(flds))
        params = dict(self.parameters)
        for p, v in params.items():
            if not isinstance(p, str) or not _NAME.match(p):
                _fail(where, f"parameter name {p!r} is not valid")
            if p in flds or p in FUNCTIONS or p in CONSTANTS or p.endswith(_SUFFIXES):
                _fail(where, f"parameter {p!r} clashes with a field, function or constant")
            params[p] = check_value(f"{where}: parameter {p}", v)
        object.__setattr__(self, "parameters", MappingProxyType(params))
        for key in _ENERGY_KEYS:
            text = getattr(self, key)
            if not isinstance(text, str) or not text.strip():
                _fail(where, f"energy.{key} must be an expression (a string), got {text!r}")
            self._trees[key] = _checked_tree(f"{where}: energy.{key}", text,
                                             self._allowed(key))
        if self.branch is not None and self.branch not in flds:
            _fail(where, f"branch {self.branch!r} is not one of the fields {list(flds)}")
        _check_kinetic(where, self._trees["kinetic"], self.fields)

    def _allowed(self, key: str) -> set:
        names = set(self.parameters) | set(FUNCTIONS) | set(CONSTANTS)
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
        """The checked syntax tree of energy ``key`` (kinetic, bond or site)."""
        return self._trees[key]

    def canonical(self) -> dict:
        """What defines the equations (not the defaults, the description or the source)."""
        return {"name": self.name, "fields": list(self.fields),
                "parameters": sorted(self.parameters),
                "energy": {k: ast.dump(self._trees[k]) for k in _ENERGY_KEYS}}

    @property
    def content_hash(self) -> str:
        """sha256 of :meth:`canonical`: the key of the derived code's cache."""
        text = json.dumps(self.canonical(), sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()

    def with_energy(self, **changes) -> Lattice:
        """A copy with some of name, fields, parameters, kinetic, bond, site replaced."""
        kw = {k: getattr(self, k) for k in ("name", "fields", "parameters", "kinetic", "bond",
                                           "site", "description", "branch", "references",
                                           "source")}
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
    """A parameter value: a finite real number (not a bool, a string or a complex)."""
    if isinstance(v, bool) or not isinstance(v, numbers.Real):
        raise ModelError(f"{where} must be a real number, got {type(v).__name__} {v!r}")
    v = float(v)
    if not math.isfinite(v):
        raise ModelError(f"{where} must be finite, got {v!r}")
    return v


_NODES = (ast.Expression, ast.BinOp, ast.UnaryOp, ast.Call, ast.Name, ast.Constant, ast.Load,
          ast.Add, ast.Sub, ast.Mult, ast.Div, ast.Pow, ast.USub, ast.UAdd)


def _checked_tree(where: str, text: str, allowed: set) -> ast.Expression:
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        _fail(where, f"syntax error in {text.strip()!r} at column {exc.offset}: {exc.msg}")
    for node in ast.walk(tree):
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitXor):
            _fail(where, f"'^' is not a power in {text.strip()!r}: write '**'")
    for node in ast.walk(tree):
        if not isinstance(node, _NODES):
            _fail(where, f"{type(node).__name__.lower()} is not allowed in {text.strip()!r} "
                         "(only numbers, names, + - * / ** and function calls)")
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and (isinstance(node.value, bool) or not isinstance(
                node.value, (int, float))):
            _fail(where, f"constant {node.value!r} is not a real number")
        if isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
                fn = getattr(node.func, "id", ast.unparse(node.func))
                _fail(where, f"unknown function {fn!r} (allowed: {', '.join(FUNCTIONS)})")
            if node.keywords or len(node.args) != 1:
                _fail(where, f"{node.func.id}() takes one argument")
        if isinstance(node, ast.Name) and not (isinstance(node.ctx, ast.Load)):
            _fail(where, "assignment is not allowed")
    for node in ast.walk(tree):
        if isinstance(node, ast.Name) and not _is_func(tree, node) and node.id not in allowed:
            _fail(where, _unknown(node.id, allowed))
    return tree


def _is_func(tree, name_node) -> bool:
    return any(isinstance(n, ast.Call) and n.func is name_node for n in ast.walk(tree))


def _unknown(name: str, allowed: set) -> str:
    hint = ""
    if re.search(r"_(next|prev)\d|_prev$|_next_next", name):
        hint = " (couplings beyond the nearest neighbour are not supported: bond couples " \
               "cell n to n + 1 only)"
    elif name.endswith("_next"):
        hint = " (u_next is allowed in energy.bond only)"
    elif name.endswith("_t"):
        hint = " (velocities are allowed in energy.kinetic only)"
    names = ", ".join(sorted(n for n in allowed if n not in FUNCTIONS and n not in CONSTANTS))
    return f"unknown symbol {name!r}{hint}; allowed here: {names}"


def _check_kinetic(where: str, tree: ast.Expression, fields: tuple):
    # A sum of terms c * u_t**2 (c free of velocities), read off the tree without SymPy;
    # derivation re-checks it symbolically (a form that only expands to one is accepted
    # there too).
    terms = []

    def walk(node, sign=1):
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub)):
            walk(node.left, sign)
            walk(node.right, sign if isinstance(node.op, ast.Add) else -sign)
        else:
            terms.append(node)

    walk(tree.body)
    seen = set()
    for t in terms:
        vel = {n.id for n in ast.walk(t) if isinstance(n, ast.Name) and n.id.endswith("_t")}
        text = ast.unparse(t)
        if len(vel) != 1:
            _fail(where, f"energy.kinetic must be a diagonal quadratic form sum_i m_i u_t**2/2"
                         f"; the term {text!r} " + ("has no velocity" if not vel else
                                                   "couples velocities " + ", ".join(
                                                       sorted(vel))))
        seen |= vel
    missing = [f for f in fields if f + "_t" not in seen]
    if missing:
        _fail(where, f"energy.kinetic has no term for field(s) {', '.join(missing)} "
                     f"(every field needs a mass: e.g. '{missing[0]}_t**2/2')")


def read_model(path: str | Path) -> Lattice:
    """Read a model file (TOML): the format of ``docs/models.md``."""
    path = Path(path)
    where = str(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ModelError(f"{where}: no such model file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ModelError(f"{where}: cannot read the model file ({exc})") from None
    return parse_model(text, where)


def parse_model(text: str, where: str = "model") -> Lattice:
    """A :class:`Lattice` from the text of a model file."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ModelError(f"{where}: not valid TOML ({exc})") from None
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
                       description=str(data.get("description", "")),
                       branch=data.get("branch"), references=str(data.get("references", "")),
                       source=where)
    except ModelError as exc:
        msg = str(exc)
        raise ModelError(msg if msg.startswith(where) else f"{where}: {msg}") from None
